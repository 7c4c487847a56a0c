//! The Lorenz attractor (Lorenz 1963; σ = 10, ρ = 28, β = 8/3, from (1, 1, 1)) and how long each
//! method's trajectory stays with the true one.
//!
//! The flow is chaotic: nearby states separate like e^{λt} with λ ≈ 0.906 (the largest Lyapunov
//! exponent, Sprott, *Chaos and Time-Series Analysis*, 2003, Table A.1), so a method with local
//! error ε follows the true trajectory only until roughly t ≈ ln(1/ε)/λ. The reference is DOP853 at
//! rtol = atol = 1e-14; a second at 1e-13 shows how far the reference itself can be trusted.
//! For each run the **departure time** is the first recorded time (every 0.01) at which its state
//! is more than 1 away from the reference (max norm).
//!
//! `cargo run --release --example lorenz` writes under `out/lorenz/`: `departure.csv` (method,
//! setting, f-evaluations, departure time), `departure.png` (departure time against cost),
//! `attractor.png` (x–z and x–y projections) and `attractor.gif` (RK4 at dt = 0.02 and the
//! reference, leaving each other).

use std::path::Path;

use odyn::output::write_table;
use odyn::plot::{Chart, Frame, Series, View, animation, views};
use odyn::prelude::*;

// The model, written once for the examples, tests and benches (`scenes/src/chaos.rs`): x′ = σ(y −
// x), y′ = x(ρ − z) − y, z′ = xy − βz.
use scenes::{Lorenz, LorenzState};

/// The end time and the recording interval.
const T_END: f64 = 40.0;
const EVERY: f64 = 0.01;

/// The Lorenz attractor (Lorenz 1963; σ = 10, ρ = 28, β = 8/3, from (1, 1, 1)) and how long each
/// method's trajectory stays with the true one.
///
/// Writes its CSV files and charts under `out/lorenz/` (the example's source says what each
/// holds).
#[derive(clap::Parser)]
struct Cli {
    /// Frames of `attractor.gif`, spread over t = 0 to 30 (150 frames at 640 pixels: ~4 MB)
    #[arg(long, default_value_t = 150)]
    gif_frames: usize,
    /// Width of `attractor.gif` in pixels (its height is 7/8 of it)
    #[arg(long, default_value_t = 640)]
    gif_width: u32,
}

fn main() -> odyn::Result<()> {
    let cli = <Cli as clap::Parser>::parse();
    let dir = Path::new("out/lorenz");
    let model = Lorenz {
        x: 1.0,
        y: 1.0,
        z: 1.0,
        sigma: 10.0,
        rho: 28.0,
        beta: 8.0 / 3.0,
    };
    let times: Vec<f64> = (1..=(T_END / EVERY).round() as usize)
        .map(|k| k as f64 * EVERY)
        .collect();
    let adaptive = |method: Method, tol: f64| {
        model
            .simulate()
            .integrator(method)
            .tolerances(tol, tol)
            .duration(T_END)
            .save_at(&times)
            .run()
    };
    let reference = adaptive(Method::Dop853, 1e-14)?;
    let check = adaptive(Method::Dop853, 1e-13)?;
    let horizon = departure(&check, &reference);
    println!(
        "Lorenz from (1, 1, 1): reference DOP853 at 1e-14 ({} steps); DOP853 at 1e-13 leaves it at \
         t = {horizon:.2}, so departures later than that are not resolved",
        reference.stats.steps
    );

    let mut runs: Vec<(&str, String, Trajectory<LorenzState>)> = Vec::new();
    for dt in [1e-3, 1e-4] {
        let run = fixed(&model, Method::ExplicitEuler, dt, &times)?;
        runs.push(("explicit Euler", format!("dt {dt:e}"), run));
    }
    for dt in [0.02, 0.01, 0.005, 0.0025, 0.00125] {
        let run = fixed(&model, Method::Rk4, dt, &times)?;
        runs.push(("RK4", format!("dt {dt}"), run));
    }
    for tol in [1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
        runs.push((
            "Tsit5",
            format!("tol {tol:e}"),
            adaptive(Method::Tsit5, tol)?,
        ));
        runs.push((
            "DOP853",
            format!("tol {tol:e}"),
            adaptive(Method::Dop853, tol)?,
        ));
    }

    println!(
        "  {:<16}{:>14}{:>14}{:>12}",
        "method", "setting", "f-evals", "departs at"
    );
    let mut rows = Vec::new();
    let mut series: Vec<(&str, Vec<(f64, f64)>)> = Vec::new();
    for (method, setting, run) in &runs {
        let t = departure(run, &reference);
        let evaluations = run.stats.evaluations as f64;
        println!(
            "  {method:<16}{setting:>14}{:>14}{t:>12.2}",
            run.stats.evaluations
        );
        rows.push(vec![
            method.to_string(),
            setting.clone(),
            run.stats.evaluations.to_string(),
            format!("{t}"),
        ]);
        match series.iter_mut().find(|(name, _)| name == method) {
            Some((_, points)) => points.push((evaluations, t)),
            None => series.push((method, vec![(evaluations, t)])),
        }
    }
    write_table(
        dir.join("departure.csv"),
        &["method", "setting", "evaluations", "departure_time"],
        &rows,
    )?;
    let mut chart_series: Vec<Series> = series
        .into_iter()
        .map(|(name, points)| Series::line_and_markers(name, points))
        .collect();
    chart_series.push(Series::line(
        "reference check (DOP853 1e-13)",
        vec![(3e3, horizon), (5e5, horizon)],
    ));
    Chart {
        title: "Lorenz: how long each run stays within 1 of the reference".into(),
        x_label: "f-evaluations".into(),
        y_label: "departure time".into(),
        log_x: true,
        series: chart_series,
        ..Chart::default()
    }
    .write(dir.join("departure.png"), (1000, 600))?;

    attractor(dir, &reference, &runs[2].2, &cli)?;
    println!("wrote out/lorenz/");
    Ok(())
}

fn fixed(
    model: &Lorenz,
    method: Method,
    dt: f64,
    times: &[f64],
) -> odyn::Result<Trajectory<LorenzState>> {
    model
        .simulate()
        .integrator(method)
        .dt(dt)
        .duration(T_END)
        .save_at(times)
        .run()
}

/// The first recorded time at which `run` is more than 1 from `reference` (max norm), or the end
/// time if it never is.
fn departure(run: &Trajectory<LorenzState>, reference: &Trajectory<LorenzState>) -> f64 {
    run.samples
        .iter()
        .zip(&reference.samples)
        .find(|(a, b)| {
            debug_assert!((a.t - b.t).abs() < 1e-9);
            (a.state.x - b.state.x)
                .abs()
                .max((a.state.y - b.state.y).abs())
                .max((a.state.z - b.state.z).abs())
                > 1.0
        })
        .map_or(T_END, |(a, _)| a.t)
}

/// The attractor in two projections, and an animation of `other` leaving the reference.
fn attractor(
    dir: &Path,
    reference: &Trajectory<LorenzState>,
    other: &Trajectory<LorenzState>,
    cli: &Cli,
) -> odyn::Result<()> {
    let path = |run: &Trajectory<LorenzState>, f: fn(&LorenzState) -> (f64, f64)| {
        run.samples
            .windows(2)
            .map(|w| [f(&w[0].state), f(&w[1].state)])
            .collect::<Vec<_>>()
    };
    let xz = |s: &LorenzState| (s.x, s.z);
    let xy = |s: &LorenzState| (s.x, s.y);
    views(
        dir.join("attractor.png"),
        "Lorenz attractor, t ≤ 40 (DOP853 at 1e-14)",
        &[
            View {
                title: "x–z".into(),
                x_label: "x".into(),
                y_label: "z".into(),
                segments: path(reference, xz),
                bounds: ((-22.0, 22.0), (0.0, 52.0)),
                ..View::default()
            },
            View {
                title: "x–y".into(),
                x_label: "x".into(),
                y_label: "y".into(),
                segments: path(reference, xy),
                bounds: ((-22.0, 22.0), (-28.0, 28.0)),
                ..View::default()
            },
        ],
        (1200, 600),
    )?;
    // `gif_frames` times evenly up to t = 30 (every 0.2 time units by default): both runs' last
    // 2 time units as trails, their current states as dots.
    let count = cli.gif_frames.clamp(1, 3000);
    let frames: Vec<Frame> = (1..=count)
        .map(|k| {
            let now = (k * 3000 / count).max(1) - 1;
            let from = now.saturating_sub(200);
            let trail = |run: &Trajectory<LorenzState>| {
                run.samples[from..=now]
                    .windows(2)
                    .map(|w| [xz(&w[0].state), xz(&w[1].state)])
                    .collect::<Vec<_>>()
            };
            Frame {
                title: format!(
                    "t = {:.1}: reference (blue), RK4 at dt = 0.02 (orange)",
                    reference.samples[now].t
                ),
                views: vec![View {
                    title: "x–z".into(),
                    x_label: "x".into(),
                    y_label: "z".into(),
                    segments: trail(reference),
                    highlighted: trail(other),
                    points: vec![
                        xz(&reference.samples[now].state),
                        xz(&other.samples[now].state),
                    ],
                    bounds: ((-22.0, 22.0), (0.0, 52.0)),
                    ..View::default()
                }],
            }
        })
        .collect();
    // The same 7.5 s loop at any frame count.
    let delay = (7500 / count as u32).max(20);
    let size = (cli.gif_width, cli.gif_width.saturating_mul(7) / 8);
    animation(dir.join("attractor.gif"), &frames, size, delay)
}
