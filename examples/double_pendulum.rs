//! The double pendulum: chaos, its Lyapunov exponent, and energy error per method.
//!
//! Two point masses m₁ = m₂ = 1 on massless rods l₁ = l₂ = 1, g = 9.81, angles from the downward
//! vertical; the equations of motion from the Lagrangian (e.g. Levien & Tan, "Double pendulum:
//! An experiment in chaos", Am. J. Phys. 61 (1993) 1038), released from rest at θ₁ = 2.0,
//! θ₂ = 2.5 rad.
//!
//! - **Chaos.** A second state starts 1e-9 rad away (in θ₁). Both are integrated with DOP853 at
//!   rtol = atol = 1e-12; their separation grows like e^{λt} until it saturates at the size of
//!   the motion. λ is fitted to ln(separation) where it lies between 1e-7 and 1e-2, and
//!   estimated independently by Benettin's method (renormalise the separation to 1e-9 every
//!   0.5 s for 200 s and average the logarithmic growth; Benettin et al., Meccanica 15 (1980) 9).
//! - **Energy.** Each method's relative energy error over 100 s. The Hamiltonian is not
//!   separable (the kinetic energy depends on θ₁ − θ₂), so the Verlet family is not symplectic
//!   here and its energy error is not bounded by theory; the forces read velocities, so the
//!   compositions cannot run at all.
//!
//! `cargo run --release --example double_pendulum` writes under `out/double_pendulum/`:
//! `separation.csv` and `separation.png` (log separation against time with the fitted line),
//! `energy.csv` and `energy.png`, and `double_pendulum.gif` (the two nearby states, overlaid,
//! until they part).

use std::path::Path;

use odyn::output::{number, write_table};
use odyn::plot::{Chart, Frame, Series, View, animation};
use odyn::prelude::*;
// The model, written once for the examples and checks: `scenes/src/pendulums.rs`.
use scenes::{DoublePendulum, DoublePendulumState};

/// The separation of two states (Euclidean, over angles and angular velocities).
fn distance(a: &DoublePendulumState, b: &DoublePendulumState) -> f64 {
    a.as_slice()
        .iter()
        .zip(b.as_slice())
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// The double pendulum: chaos, its Lyapunov exponent, and energy error per method.
///
/// Writes its CSV files and charts under `out/double_pendulum/` (the example's source says what
/// each
/// holds); takes no options.
#[derive(clap::Parser)]
struct Cli {}

fn main() -> odyn::Result<()> {
    <Cli as clap::Parser>::parse();
    let dir = Path::new("out/double_pendulum");
    let model = DoublePendulum::released();
    let every = 0.01;
    let times: Vec<f64> = (1..=3000).map(|k| f64::from(k) * every).collect();
    let tight = |state: DoublePendulumState| {
        model
            .simulate()
            .integrator(Method::Dop853)
            .tolerances(1e-12, 1e-12)
            .initial_state(state)
            .duration(30.0)
            .save_at(&times)
            .run()
    };
    let mut nearby = model.state();
    nearby.theta1 += 1e-9;
    let (a, b) = (tight(model.state())?, tight(nearby)?);
    let separation: Vec<(f64, f64)> = a
        .samples
        .iter()
        .zip(&b.samples)
        .map(|(p, q)| (p.t, distance(&p.state, &q.state)))
        .collect();
    let window: Vec<(f64, f64)> = separation
        .iter()
        .filter(|(_, d)| (1e-7..1e-2).contains(d))
        .map(|&(t, d)| (t, d.ln()))
        .collect();
    let (slope, intercept) = fit(&window);
    let benettin = benettin(&model)?;
    println!(
        "Double pendulum from θ = (2.0, 2.5) rad at rest; a second state 1e-9 rad away:\n  \
         separation reaches 1e-2 at t = {:.2} s; fitted growth rate λ = {slope:.3} /s over \
         t = {:.1} … {:.1} s; Benettin's estimate over 200 s: λ = {benettin:.3} /s",
        window.last().map_or(f64::NAN, |p| p.0),
        window.first().map_or(f64::NAN, |p| p.0),
        window.last().map_or(f64::NAN, |p| p.0),
    );
    write_table(
        dir.join("separation.csv"),
        &["t", "separation"],
        &separation
            .iter()
            .map(|&(t, d)| vec![number(t), number(d)])
            .collect::<Vec<_>>(),
    )?;
    let fitted = window
        .first()
        .zip(window.last())
        .map(|(s, e)| {
            vec![
                (s.0, (intercept + slope * s.0).exp()),
                (e.0, (intercept + slope * e.0).exp()),
            ]
        })
        .unwrap_or_default();
    Chart {
        title: format!(
            "Double pendulum: states 1e-9 apart (λ fit {slope:.2}, Benettin {benettin:.2})"
        ),
        x_label: "t [s]".into(),
        y_label: "separation".into(),
        log_y: true,
        series: vec![
            Series::line("separation (DOP853, tol 1e-12)", separation),
            Series::line(format!("e^(λt), λ = {slope:.2}"), fitted),
        ],
        ..Chart::default()
    }
    .write(dir.join("separation.png"), (1000, 600))?;

    energy(dir, &model)?;
    motion(dir, &a, &b)?;
    println!("wrote out/double_pendulum/");
    Ok(())
}

/// Least-squares line through `points`: (slope, intercept).
fn fit(points: &[(f64, f64)]) -> (f64, f64) {
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let num: f64 = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let den: f64 = points.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    let slope = num / den;
    (slope, my - slope * mx)
}

/// Benettin's estimate of the largest Lyapunov exponent: 400 renormalisations every 0.5 s.
fn benettin(model: &DoublePendulum) -> odyn::Result<f64> {
    let (d0, tau, rounds) = (1e-9, 0.5, 400);
    let mut reference = model.state();
    let mut other = reference;
    other.theta1 += d0;
    let mut sum = 0.0;
    for round in 0..rounds {
        let start = f64::from(round) * tau;
        let advance = |state: &DoublePendulumState| -> odyn::Result<DoublePendulumState> {
            let run = model
                .simulate()
                .integrator(Method::Dop853)
                .tolerances(1e-12, 1e-12)
                .start_time(start)
                .initial_state(*state)
                .duration(tau)
                .record_every(u64::MAX)
                .run()?;
            Ok(run.last().state)
        };
        reference = advance(&reference)?;
        other = advance(&other)?;
        let d = distance(&reference, &other);
        sum += (d / d0).ln();
        let (r, o) = (reference.as_slice().to_vec(), other.as_mut_slice());
        for (oi, ri) in o.iter_mut().zip(&r) {
            *oi = ri + (*oi - ri) * d0 / d;
        }
    }
    Ok(sum / (f64::from(rounds) * tau))
}

/// Relative energy error over 100 s per method.
fn energy(dir: &Path, model: &DoublePendulum) -> odyn::Result<()> {
    let e0 = Model::energy(model, &model.state()).expect("the model defines its energy");
    let duration = 100.0;
    let mut runs = Vec::new();
    for method in [Method::VelocityVerlet, Method::Leapfrog, Method::Rk4] {
        for dt in [1e-3, 1e-4] {
            let run = model
                .simulate()
                .integrator(method)
                .dt(dt)
                .duration(duration)
                .record_every((0.05 / dt).round() as u64)
                .run()?;
            runs.push((format!("{} (dt = {dt:e})", method.label()), run));
        }
    }
    for tol in [1e-8, 1e-12] {
        let run = model
            .simulate()
            .integrator(Method::Dop853)
            .tolerances(tol, tol)
            .duration(duration)
            .save_at(&(1..=2000).map(|k| f64::from(k) * 0.05).collect::<Vec<_>>())
            .run()?;
        runs.push((format!("DOP853 (tol {tol:e})"), run));
    }
    println!("  energy error over {duration} s (E₀ = {e0:.6}):");
    println!(
        "    {:<28}{:>12}{:>16}{:>16}",
        "method", "f-evals", "max |ΔE/E₀|", "final |ΔE/E₀|"
    );
    let mut rows = Vec::new();
    let mut series = Vec::new();
    for (label, run) in &runs {
        let errors: Vec<(f64, f64)> = run
            .samples
            .iter()
            .map(|s| (s.t, ((s.energy.unwrap_or(f64::NAN) - e0) / e0).abs()))
            .collect();
        let max = errors.iter().map(|p| p.1).fold(0.0, f64::max);
        let last = errors.last().map_or(f64::NAN, |p| p.1);
        println!(
            "    {label:<28}{:>12}{max:>16.3e}{last:>16.3e}",
            run.stats.evaluations
        );
        rows.push(vec![
            label.clone(),
            run.stats.evaluations.to_string(),
            number(max),
            number(last),
        ]);
        series.push(Series::line(label.clone(), errors));
    }
    write_table(
        dir.join("energy.csv"),
        &[
            "method",
            "evaluations",
            "max_relative_energy_error",
            "final_relative_energy_error",
        ],
        &rows,
    )?;
    Chart {
        title: "Double pendulum: relative energy error over 100 s".into(),
        x_label: "t [s]".into(),
        y_label: "|E − E₀| / |E₀|".into(),
        log_y: true,
        series,
        ..Chart::default()
    }
    .write(dir.join("energy.png"), (1000, 600))
}

/// The two nearby states overlaid, every 0.2 s up to 25 s.
fn motion(
    dir: &Path,
    a: &Trajectory<DoublePendulumState>,
    b: &Trajectory<DoublePendulumState>,
) -> odyn::Result<()> {
    let arms = |s: &DoublePendulumState| {
        let p1 = (s.theta1.sin(), -s.theta1.cos());
        let p2 = (p1.0 + s.theta2.sin(), p1.1 - s.theta2.cos());
        (vec![[(0.0, 0.0), p1], [p1, p2]], p2)
    };
    let frames: Vec<Frame> = (0..=125)
        .map(|k| {
            let (sa, sb) = (&a.samples[20 * k], &b.samples[20 * k]);
            let ((first, tip_a), (second, tip_b)) = (arms(&sa.state), arms(&sb.state));
            Frame {
                title: format!(
                    "t = {:.1} s, separation {:.1e}",
                    sa.t,
                    distance(&sa.state, &sb.state)
                ),
                views: vec![View {
                    title: "two states 1e-9 rad apart".into(),
                    segments: first,
                    highlighted: second,
                    points: vec![tip_a, tip_b],
                    bounds: ((-2.2, 2.2), (-2.2, 2.2)),
                    line_width: 3,
                    ..View::default()
                }],
            }
        })
        .collect();
    animation(dir.join("double_pendulum.gif"), &frames, (420, 460), 80)
}
