//! A large-amplitude pendulum against its exact solution.
//!
//! θ″ = −ω₀²·sin θ with ω₀² = g/L = 9.81, released from rest at θ₀ = 2.5 rad (143°). With
//! k = sin(θ₀/2) the exact period is T = 4K(k)/ω₀, K the complete elliptic integral of the first
//! kind, K(k) = π / (2·AGM(1, √(1 − k²))) (Gauss), and the exact motion is
//! θ(t) = 2·arcsin(k·sn(K − ω₀t, k)) with sn Jacobi's elliptic sine, computed by the descending
//! Landen (AGM) transformation (Abramowitz & Stegun, *Handbook of Mathematical Functions*, §16.4,
//! and §17.6 for the AGM). The small-angle period 2π/ω₀ is only 0.61 of the true one at this amplitude.
//!
//! For each method at dt = T/100 (and DOP853 at two tolerances) the example measures, over 20
//! periods: the period (from the times θ crosses zero upwards, interpolated linearly), the
//! largest energy error, and the angle error against the exact θ(t).
//!
//! `cargo run --release --example pendulum` writes under `out/pendulum/`: `pendulum.csv`,
//! `energy.png` (energy error against time, log scale), `angle_error.png` and `pendulum.gif`
//! (the exact pendulum and leapfrog at dt = T/25, side by side, over two periods).

use std::f64::consts::PI;
use std::path::Path;

use odyn::output::{number, write_table};
use odyn::plot::{Chart, Frame, Series, View, animation};
use odyn::prelude::*;

/// A simple pendulum of length L under gravity g.
#[system]
#[derive(Clone, Copy)]
pub struct Pendulum {
    /// Angle from the downward vertical (rad).
    #[position]
    pub theta: f64,
    /// Angular velocity (rad/s).
    #[velocity]
    pub omega: f64,
    /// g/L (1/s²).
    pub omega0_squared: f64,
}

#[system]
impl Pendulum {
    fn acceleration(&self) -> f64 {
        -self.omega0_squared * self.theta.sin()
    }

    /// Energy per unit m·L²: ½θ′² + ω₀²(1 − cos θ).
    fn energy(&self) -> f64 {
        0.5 * self.omega * self.omega + self.omega0_squared * (1.0 - self.theta.cos())
    }
}

/// The arithmetic–geometric mean of a and b.
fn agm(mut a: f64, mut b: f64) -> f64 {
    while (a - b).abs() > 1e-16 * a {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    a
}

/// K(k), the complete elliptic integral of the first kind (modulus k): π / (2·AGM(1, k′)).
fn complete_k(k: f64) -> f64 {
    PI / (2.0 * agm(1.0, (1.0 - k * k).sqrt()))
}

/// Jacobi's sn(u, k) by the descending Landen transformation (A&S 16.4.3): aₙ, bₙ, cₙ of the
/// AGM from (1, k′, k), φ_N = 2ᴺ·a_N·u, then φₙ₋₁ = (φₙ + arcsin(cₙ/aₙ · sin φₙ))/2; sn = sin φ₀.
fn sn(u: f64, k: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - k * k).sqrt());
    let mut ratios = Vec::new();
    while (a - b).abs() > 1e-16 * a {
        let c = 0.5 * (a - b);
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
        ratios.push(c / a);
    }
    let mut phi = 2f64.powi(ratios.len() as i32) * a * u;
    for r in ratios.iter().rev() {
        phi = 0.5 * (phi + (r * phi.sin()).asin());
    }
    phi.sin()
}

/// A large-amplitude pendulum against its exact solution.
///
/// Writes its CSV files and charts under `out/pendulum/` (the example's source says what each
/// holds); takes no options.
#[derive(clap::Parser)]
struct Cli {}

fn main() -> odyn::Result<()> {
    <Cli as clap::Parser>::parse();
    let dir = Path::new("out/pendulum");
    let (theta0, omega0_squared): (f64, f64) = (2.5, 9.81);
    let omega0 = f64::sqrt(omega0_squared);
    let k = (theta0 / 2.0).sin();
    let quarter = complete_k(k);
    let period = 4.0 * quarter / omega0;
    let exact = |t: f64| 2.0 * (k * sn(quarter - omega0 * t, k)).asin();
    let model = Pendulum {
        theta: theta0,
        omega: 0.0,
        omega0_squared,
    };
    let e0 = Model::energy(&model, &model.state()).expect("the model defines its energy");
    let periods = 20.0;
    println!(
        "Pendulum from rest at θ₀ = {theta0} rad: exact period 4K(k)/ω₀ = {period:.12} s \
         (k = {k:.6}, K = {quarter:.12}); small-angle 2π/ω₀ = {:.6} s",
        2.0 * PI / omega0
    );

    let dt = period / 100.0;
    let mut runs: Vec<(String, Trajectory<PendulumState>)> = Vec::new();
    for method in [
        Method::SymplecticEuler,
        Method::VelocityVerlet,
        Method::Leapfrog,
        Method::Yoshida4,
        Method::KahanLi6,
        Method::Rk4,
    ] {
        let run = model
            .simulate()
            .integrator(method)
            .dt(dt)
            .steps((100.0 * periods) as u64)
            .run()?;
        runs.push((format!("{} (dt = T/100)", method.label()), run));
    }
    for tol in [1e-6, 1e-10] {
        let run = model
            .simulate()
            .integrator(Method::Dop853)
            .tolerances(tol, tol)
            .duration(periods * period)
            .save_at(
                &(1..=2000)
                    .map(|i| f64::from(i) * periods * period / 2000.0)
                    .collect::<Vec<_>>(),
            )
            .run()?;
        runs.push((format!("DOP853 (tol {tol:e})"), run));
    }

    println!(
        "  {:<28}{:>10}{:>16}{:>14}{:>14}",
        "method", "f-evals", "period error", "max |ΔE|/E₀", "max |Δθ|"
    );
    let mut rows = Vec::new();
    let (mut energy_series, mut angle_series) = (Vec::new(), Vec::new());
    for (label, run) in &runs {
        let measured = measured_period(run);
        let energy: Vec<(f64, f64)> = run
            .samples
            .iter()
            .map(|s| (s.t, (s.energy.unwrap_or(f64::NAN) - e0).abs() / e0))
            .collect();
        let angle: Vec<(f64, f64)> = run
            .samples
            .iter()
            .map(|s| (s.t, (s.state.theta - exact(s.t)).abs()))
            .collect();
        let max = |v: &[(f64, f64)]| v.iter().map(|p| p.1).fold(0.0, f64::max);
        println!(
            "  {label:<28}{:>10}{:>16.3e}{:>14.3e}{:>14.3e}",
            run.stats.evaluations,
            measured - period,
            max(&energy),
            max(&angle)
        );
        rows.push(vec![
            label.clone(),
            run.stats.evaluations.to_string(),
            number(measured),
            number(measured - period),
            number(max(&energy)),
            number(max(&angle)),
        ]);
        energy_series.push(Series::line(label.clone(), energy));
        angle_series.push(Series::line(label.clone(), angle));
    }
    write_table(
        dir.join("pendulum.csv"),
        &[
            "method",
            "evaluations",
            "period",
            "period_error",
            "max_energy_error",
            "max_angle_error",
        ],
        &rows,
    )?;
    Chart {
        title: format!("Pendulum, θ₀ = {theta0} rad: energy error over {periods} periods"),
        x_label: "t [s]".into(),
        y_label: "|E − E₀| / E₀".into(),
        log_y: true,
        series: energy_series,
        ..Chart::default()
    }
    .write(dir.join("energy.png"), (1000, 600))?;
    Chart {
        title: "Pendulum: angle error against the exact solution 2·arcsin(k·sn(K − ω₀t, k))".into(),
        x_label: "t [s]".into(),
        y_label: "|θ − θ_exact| [rad]".into(),
        log_y: true,
        series: angle_series,
        ..Chart::default()
    }
    .write(dir.join("angle_error.png"), (1000, 600))?;
    swing(dir, &model, period, &exact)?;
    println!("wrote out/pendulum/");
    Ok(())
}

/// The mean spacing of the upward zero crossings of θ, each located by linear interpolation.
fn measured_period(run: &Trajectory<PendulumState>) -> f64 {
    let crossings: Vec<f64> = run
        .samples
        .windows(2)
        .filter(|w| w[0].state.theta < 0.0 && w[1].state.theta >= 0.0)
        .map(|w| {
            let (a, b) = (w[0].state.theta, w[1].state.theta);
            w[0].t + (w[1].t - w[0].t) * (-a / (b - a))
        })
        .collect();
    match (crossings.first(), crossings.last()) {
        (Some(first), Some(last)) if crossings.len() > 1 => {
            (last - first) / (crossings.len() - 1) as f64
        }
        _ => f64::NAN,
    }
}

/// Two periods of the exact pendulum (left) beside leapfrog at dt = T/25 (right).
fn swing(
    dir: &Path,
    model: &Pendulum,
    period: f64,
    exact: &dyn Fn(f64) -> f64,
) -> odyn::Result<()> {
    let run = model
        .simulate()
        .integrator(Method::Leapfrog)
        .dt(period / 25.0)
        .steps(50)
        .run()?;
    let rod = |theta: f64, title: &str| View {
        title: title.into(),
        segments: vec![[(0.0, 0.0), (theta.sin(), -theta.cos())]],
        points: vec![(theta.sin(), -theta.cos())],
        bounds: ((-1.2, 1.2), (-1.2, 1.2)),
        line_width: 3,
        ..View::default()
    };
    let frames: Vec<Frame> = run
        .samples
        .iter()
        .map(|s| Frame {
            title: format!("t = {:.2} s", s.t),
            views: vec![
                rod(exact(s.t), "exact"),
                rod(s.state.theta, "leapfrog, dt = T/25"),
            ],
        })
        .collect();
    animation(dir.join("pendulum.gif"), &frames, (640, 360), 60)
}
