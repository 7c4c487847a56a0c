//! N-body orbits: the outer solar system over 2·10⁵ days and the Chenciner–Montgomery
//! figure-eight, integrated by leapfrog, the leapfrog compositions (Yoshida 4, Yoshida 6,
//! Kahan–Li 6) and RK4 at fixed steps, and by DOP853 with tolerances.
//!
//! - **Outer solar system** (Hairer, Lubich & Wanner, *Geometric Numerical Integration*, 2nd ed.,
//!   2006, §I.2.4, Table 2.1): the Sun (with the inner planets' mass), Jupiter, Saturn, Uranus,
//!   Neptune and Pluto on 5 September 1994, moved to the barycentric frame; masses relative to the Sun, distances in AU, time in
//!   days, G = 2.95912208286·10⁻⁴. Run for 2·10⁵ days (17 Jupiter years, 2.2 Pluto years) at
//!   dt = 10 days. The symplectic methods keep the energy error bounded; RK4's drifts secularly.
//! - **Figure-eight** (A. Chenciner & R. Montgomery, Ann. of Math. 152 (2000) 881; initial data
//!   and period T = 6.32591398 from C. Simó's computation as quoted there): three equal masses,
//!   G = 1, chase each other along one curve; after one period each returns to its start. The
//!   distance from the start after one period measures each method's error.
//!
//! `cargo run --release --example nbody` writes under `out/nbody/`: `solar_system.csv` (time,
//! relative energy error and relative angular-momentum error per method), `solar_energy.png`,
//! `solar_momentum.png` (log plots), `solar_orbits.png` (the orbits projected on the ecliptic
//! plane, from the Kahan–Li run), `figure_eight.csv` (return error against steps per period) and
//! `figure_eight.gif` (one period, animated).

use std::path::Path;

use odyn::output::write_table;
use odyn::plot::{Chart, Frame, Series, View, animation, views};
use odyn::prelude::*;

/// Bodies of the outer solar system.
const N: usize = 6;

// The outer solar system (HLW 2006, Table 2.1), shared with the tests: positions and
// velocities `[Vector3<f64>; 6]`, r̈ᵢ = Σⱼ G mⱼ (rⱼ − rᵢ)/|rⱼ − rᵢ|³, its energy, and
// `SolarSystem::outer()` (the table's data moved to the barycentric frame).
use scenes::SolarSystem;

/// Three equal masses in the plane, G = m = 1.
#[system(jacobian = false)]
#[derive(Clone, Copy)]
pub struct ThreeBodies {
    /// x coordinates.
    #[position]
    pub x: [f64; 3],
    /// y coordinates.
    #[position]
    pub y: [f64; 3],
    /// x velocities.
    #[velocity]
    pub u: [f64; 3],
    /// y velocities.
    #[velocity]
    pub v: [f64; 3],
}

#[system]
impl ThreeBodies {
    fn acceleration(&self) -> ([f64; 3], [f64; 3]) {
        let mut ax = [0.0; 3];
        let mut ay = [0.0; 3];
        for i in 0..3 {
            for j in (i + 1)..3 {
                let dx = self.x[j] - self.x[i];
                let dy = self.y[j] - self.y[i];
                let r2 = dx * dx + dy * dy;
                let s = 1.0 / (r2 * r2.sqrt());
                ax[i] += s * dx;
                ay[i] += s * dy;
                ax[j] -= s * dx;
                ay[j] -= s * dy;
            }
        }
        (ax, ay)
    }
}

/// The methods compared at a fixed step.
const FIXED: [Method; 5] = [
    Method::Leapfrog,
    Method::Yoshida4,
    Method::Yoshida6,
    Method::KahanLi6,
    Method::Rk4,
];

/// N-body orbits: the outer solar system and the Chenciner–Montgomery figure-eight, by leapfrog,
/// its compositions and the adaptive methods, with energy and angular-momentum errors.
///
/// Writes its CSV files and charts under `out/nbody/` (the example's source says what each
/// holds).
#[derive(clap::Parser)]
struct Cli {
    /// Frames of `figure_eight.gif`, at most 121 (121: ~2.3 MB)
    #[arg(long, default_value_t = 121)]
    gif_frames: usize,
}

fn main() -> odyn::Result<()> {
    let cli = <Cli as clap::Parser>::parse();
    let dir = Path::new("out/nbody");
    let model = SolarSystem::outer();
    let (days, dt) = (2e5, 10.0);
    let e0 = Model::energy(&model, &model.state()).expect("the model defines its energy");
    let l0 = model.angular_momentum(&model.state());

    println!("Outer solar system, {days:e} days (HLW Table 2.1); |ΔE/E₀| and |ΔL|/|L₀|:");
    println!(
        "  {:<18}{:>4}{:>10}{:>14}{:>18}{:>12}",
        "method", "dt", "steps", "max |ΔE/E₀|", "final |ΔL|/|L₀|", "f-evals"
    );
    let mut runs = Vec::new();
    for method in FIXED {
        let run = model
            .simulate()
            .integrator(method)
            .dt(dt)
            .duration(days)
            .record_every(20)
            .run()?;
        runs.push((method.label().to_string(), run));
    }
    let adaptive = model
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-10, 1e-10)
        .duration(days)
        .run()?;
    runs.push(("DOP853, tol 1e-10".to_string(), adaptive));

    let mut energy_series = Vec::new();
    let mut momentum_series = Vec::new();
    let mut rows = Vec::new();
    for (label, run) in &runs {
        let energy: Vec<(f64, f64)> = run
            .samples
            .iter()
            .map(|s| (s.t, (s.energy.unwrap_or(f64::NAN) - e0).abs() / e0.abs()))
            .collect();
        let momentum: Vec<(f64, f64)> = run
            .samples
            .iter()
            .map(|s| {
                let l = model.angular_momentum(&s.state);
                (s.t, (l - l0).norm() / l0.norm())
            })
            .collect();
        let max_energy = energy.iter().map(|p| p.1).fold(0.0, f64::max);
        println!(
            "  {:<18}{:>4}{:>10}{:>14.2e}{:>18.2e}{:>12}",
            label,
            if label.starts_with("DOP") {
                "—".to_string()
            } else {
                format!("{dt}")
            },
            run.stats.steps,
            max_energy,
            momentum.last().map_or(f64::NAN, |p| p.1),
            run.stats.evaluations
        );
        for (e, l) in energy.iter().zip(&momentum) {
            rows.push(vec![
                label.clone(),
                format!("{}", e.0),
                format!("{:e}", e.1),
                format!("{:e}", l.1),
            ]);
        }
        energy_series.push(Series::line(label.clone(), energy));
        momentum_series.push(Series::line(label.clone(), momentum));
    }
    write_table(
        dir.join("solar_system.csv"),
        &[
            "method",
            "t_days",
            "relative_energy_error",
            "relative_angular_momentum_error",
        ],
        &rows,
    )?;
    Chart {
        title: format!("Outer solar system: energy error, dt = {dt} days"),
        x_label: "t [days]".into(),
        y_label: "|E − E₀| / |E₀|".into(),
        log_y: true,
        series: energy_series,
        ..Chart::default()
    }
    .write(dir.join("solar_energy.png"), (1000, 600))?;
    Chart {
        title: "Outer solar system: angular-momentum error".into(),
        x_label: "t [days]".into(),
        y_label: "|L − L₀| / |L₀|".into(),
        log_y: true,
        series: momentum_series,
        ..Chart::default()
    }
    .write(dir.join("solar_momentum.png"), (1000, 600))?;

    // The orbits on the ecliptic (x–y), from the Kahan–Li run.
    let (_, orbit_run) = &runs[3];
    let mut segments = Vec::new();
    for pair in orbit_run.samples.windows(2) {
        for i in 1..N {
            segments.push([
                (pair[0].state.r[i].x, pair[0].state.r[i].y),
                (pair[1].state.r[i].x, pair[1].state.r[i].y),
            ]);
        }
    }
    let last = &orbit_run.last().state;
    views(
        dir.join("solar_orbits.png"),
        "Outer solar system, 2·10⁵ days (Kahan–Li 6, dt = 10 days)",
        &[View {
            title: "ecliptic (x–y), AU".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            segments,
            points: (0..N).map(|i| (last.r[i].x, last.r[i].y)).collect(),
            bounds: ((-50.0, 50.0), (-50.0, 50.0)),
            ..View::default()
        }],
        (800, 800),
    )?;

    figure_eight(dir, cli.gif_frames)?;
    println!("wrote out/nbody/");
    Ok(())
}

/// The figure-eight after one period at several step counts: max-norm distance from the start.
fn figure_eight(dir: &Path, gif_frames: usize) -> odyn::Result<()> {
    // Chenciner & Montgomery (2000), Simó's initial data: x₁ = −x₂, x₃ = 0, v₁ = v₂ = −v₃/2.
    let (px, py) = (0.97000436, -0.24308753);
    let (vx, vy) = (-0.93240737, -0.86473146);
    let bodies = ThreeBodies {
        x: [px, -px, 0.0],
        y: [py, -py, 0.0],
        u: [-vx / 2.0, -vx / 2.0, vx],
        v: [-vy / 2.0, -vy / 2.0, vy],
    };
    let period = 6.32591398;
    println!("\nFigure-eight, one period T = {period}: max distance from the start");
    println!(
        "  {:<12}{:>10}{:>12}{:>12}",
        "method", "steps", "error", "f-evals"
    );
    let start = bodies.state();
    let mut rows = Vec::new();
    for method in FIXED {
        for steps in [100u64, 1000, 10000] {
            let run = bodies
                .simulate()
                .integrator(method)
                .dt(period / steps as f64)
                .steps(steps)
                .record_every(u64::MAX)
                .run()?;
            let end = &run.last().state;
            let error = end
                .as_slice()
                .iter()
                .zip(start.as_slice())
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            println!(
                "  {:<12}{steps:>10}{error:>12.2e}{:>12}",
                method.label(),
                run.stats.evaluations
            );
            rows.push(vec![
                method.name().to_string(),
                steps.to_string(),
                format!("{error:e}"),
                run.stats.evaluations.to_string(),
            ]);
        }
    }
    // One period as an animation: the bodies with 40-sample trails (Kahan–Li 6, 600 steps).
    let run = bodies
        .simulate()
        .integrator(Method::KahanLi6)
        .dt(period / 600.0)
        .steps(600)
        .record_every(5)
        .run()?;
    let stride = run.samples.len().div_ceil(gif_frames.max(1));
    let frames: Vec<Frame> = (0..run.samples.len())
        .step_by(stride)
        .map(|k| {
            let trail = &run.samples[k.saturating_sub(40)..=k];
            let segments = trail
                .windows(2)
                .flat_map(|w| {
                    (0..3).map(move |i| {
                        [
                            (w[0].state.x[i], w[0].state.y[i]),
                            (w[1].state.x[i], w[1].state.y[i]),
                        ]
                    })
                })
                .collect();
            let now = &run.samples[k].state;
            Frame {
                title: format!("Figure-eight, t = {:.2} of T = {period}", run.samples[k].t),
                views: vec![View {
                    title: "three equal masses (Kahan–Li 6)".into(),
                    x_label: "x".into(),
                    y_label: "y".into(),
                    segments,
                    points: (0..3).map(|i| (now.x[i], now.y[i])).collect(),
                    bounds: ((-1.2, 1.2), (-0.6, 0.6)),
                    ..View::default()
                }],
            }
        })
        .collect();
    // The same ~4.8 s loop at any frame count.
    let delay = (40 * stride as u32).min(1000);
    animation(dir.join("figure_eight.gif"), &frames, (640, 400), delay)?;
    write_table(
        dir.join("figure_eight.csv"),
        &["method", "steps", "error", "evaluations"],
        &rows,
    )
}
