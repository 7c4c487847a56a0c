//! A bouncing ball, the classic event: ÿ = −g from a height H, and at every impact the velocity
//! reverses and loses a fraction (restitution e < 1). The bounce times have a closed form:
//! t₁ = √(2H/g), tₖ₊₁ = tₖ + 2·eᵏ·g·t₁/g, so every method's event location can be checked.
//!
//! `cargo run --release --example bouncing_ball` writes under `out/bouncing_ball/`:
//! `bounces.csv` (`method,dt_or_rtol,bounce,t,t_exact,relative_error`, the first 10 bounces of
//! every method — Tsit5 and DOP853 adaptive at rtol = 1e-10, the fixed-step methods at
//! dt = 1e-3), `height.png` (height against time, sampled on the dense output) and
//! `convergence.csv` (each fixed-step method's worst bounce-time error at three steps).

#![forbid(unsafe_code)]

use std::path::Path;

use odyn::output::{number, write_table};
use odyn::plot::{Chart, Series};
use odyn::prelude::*;

/// A ball in free fall, ÿ = −g.
#[system]
pub struct Ball {
    /// Height above the ground (m).
    #[position]
    pub y: f64,
    /// Vertical velocity (m/s).
    #[velocity]
    pub v: f64,
    /// Gravitational acceleration (m/s²).
    pub g: f64,
}

#[system]
impl Ball {
    fn acceleration(&self) -> f64 {
        -self.g
    }

    fn energy(&self) -> f64 {
        0.5 * self.v * self.v + self.g * self.y
    }
}

const HEIGHT: f64 = 10.0;
const G: f64 = 9.81;
const RESTITUTION: f64 = 0.8;
const BOUNCES: usize = 10;

/// The first `BOUNCES` impact times: the k-th bounce leaves at eᵏ·v₁ and lands 2eᵏ·v₁/g later.
fn exact_bounces() -> Vec<f64> {
    let t1 = (2.0 * HEIGHT / G).sqrt();
    let v1 = G * t1;
    let mut times = vec![t1];
    for k in 1..BOUNCES as i32 {
        let last = times[times.len() - 1];
        times.push(last + 2.0 * RESTITUTION.powi(k) * v1 / G);
    }
    times
}

/// The bounce, an event that reverses the velocity at y = 0 with restitution.
fn bounce() -> Event<'static, BallState> {
    Event::crossing("ground", |_, s: &BallState| s.y)
        .falling()
        .change(|_, s: &mut BallState| s.v *= -RESTITUTION)
}

/// A bouncing ball, the classic event: ÿ = −g from a height H, and at every impact the velocity
/// reverses and loses a fraction (restitution e < 1).
///
/// Writes its CSV files and charts under `out/bouncing_ball/` (the example's source says what each
/// holds); takes no options.
#[derive(clap::Parser)]
struct Cli {}

fn main() -> odyn::Result<()> {
    <Cli as clap::Parser>::parse();
    let dir = Path::new("out/bouncing_ball");
    let ball = Ball {
        y: HEIGHT,
        v: 0.0,
        g: G,
    };
    let exact = exact_bounces();
    let end = exact[BOUNCES - 1] + 0.05;
    println!(
        "bouncing ball: H = {HEIGHT} m, g = {G} m/s², e = {RESTITUTION}; first {BOUNCES} bounces \
         to t = {:.4} s",
        exact[BOUNCES - 1]
    );
    println!(
        "  {:<17} {:>12} {:>8} {:>12} {:>14}",
        "method", "dt or rtol", "bounces", "steps", "worst rel err"
    );
    let mut rows = Vec::new();
    let mut curves = Vec::new();
    for method in Method::ALL {
        let sim = ball
            .simulate()
            .integrator(method)
            .duration(end)
            .event(bounce());
        let (sim, setting) = if method.is_adaptive() {
            (sim.tolerances(1e-10, 1e-12), "rtol 1e-10".to_owned())
        } else {
            (sim.dt(1e-3), "dt 1e-3".to_owned())
        };
        let run = match sim.dense_output(true).run() {
            Ok(run) => run,
            Err(error @ odyn::Error::Unsupported { .. }) => {
                println!("  {:<17} not run: {error}", method.name());
                continue;
            }
            Err(error) => return Err(error),
        };
        let mut worst: f64 = 0.0;
        for (k, (event, t_exact)) in run.events.iter().zip(&exact).enumerate() {
            let relative = (event.t - t_exact) / t_exact;
            worst = worst.max(relative.abs());
            rows.push(vec![
                method.name().to_owned(),
                setting.clone(),
                (k + 1).to_string(),
                number(event.t),
                number(*t_exact),
                number(relative),
            ]);
        }
        println!(
            "  {:<17} {setting:>12} {:>8} {:>12} {worst:>14.2e}",
            method.name(),
            run.events.len().min(BOUNCES),
            run.steps()
        );
        if matches!(
            method,
            Method::Dop853 | Method::SymplecticEuler | Method::ExplicitEuler
        ) {
            let points: Vec<(f64, f64)> = (0..=2000)
                .map(|i| end * f64::from(i) / 2000.0)
                .filter_map(|t| Some((t, run.at(t).ok()?.y)))
                .collect();
            curves.push(Series::line(
                format!("{} ({setting})", method.label()),
                points,
            ));
        }
    }
    write_table(
        dir.join("bounces.csv"),
        &[
            "method",
            "dt_or_rtol",
            "bounce",
            "t",
            "t_exact",
            "relative_error",
        ],
        &rows,
    )?;
    Chart {
        title: format!("Bouncing ball, e = {RESTITUTION}: height on the dense output"),
        x_label: "t (s)".into(),
        y_label: "height (m)".into(),
        series: curves,
        ..Chart::default()
    }
    .write(dir.join("height.png"), (1000, 560))?;
    convergence(&ball, &exact, dir)?;
    println!(
        "wrote {}/{{bounces.csv,height.png,convergence.csv}}",
        dir.display()
    );
    Ok(())
}

/// Each fixed-step method's worst bounce-time error at dt = 4e-3, 2e-3, 1e-3 and the observed
/// order. Methods exact on a parabola (the Verlet family, RK4) sit at round-off.
fn convergence(ball: &Ball, exact: &[f64], dir: &Path) -> odyn::Result<()> {
    println!("  fixed-step convergence of the worst bounce-time error:");
    let dts = [4e-3, 2e-3, 1e-3];
    let mut rows = Vec::new();
    for method in Method::ALL.into_iter().filter(|m| !m.is_adaptive()) {
        let mut errors = Vec::new();
        for dt in dts {
            let run = match ball
                .simulate()
                .integrator(method)
                .dt(dt)
                .duration(exact[BOUNCES - 1] + 0.05)
                .record_every(u64::MAX)
                .event(bounce())
                .run()
            {
                Ok(run) => run,
                Err(odyn::Error::Unsupported { .. }) => break,
                Err(error) => return Err(error),
            };
            let worst = run
                .events
                .iter()
                .zip(exact)
                .map(|(e, t)| ((e.t - t) / t).abs())
                .fold(0.0, f64::max);
            errors.push(worst);
            rows.push(vec![method.name().to_owned(), number(dt), number(worst)]);
        }
        if let [first, .., last] = errors[..] {
            let order = (first / last).log2() / 2.0;
            let verdict = if first.max(last) < 1e-10 {
                "exact on a parabola: round-off only".to_owned()
            } else {
                format!("order {order:.2}")
            };
            println!(
                "    {:<17} {:.2e} → {:.2e}: {verdict}",
                method.name(),
                first,
                last
            );
        }
    }
    write_table(
        dir.join("convergence.csv"),
        &["method", "dt", "worst_relative_error"],
        &rows,
    )
}
