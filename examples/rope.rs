//! A rope three ways: rigid links solved by XPBD (`odyn::xpbd`: position-based dynamics with
//! substeps, Macklin et al. 2016 and 2019), the same rope as stiff springs stepped by implicit
//! Euler, and as rigid rods whose forces are algebraic components (a differential–algebraic
//! field model, `scenes::RodRope`) under Rodas5P.
//!
//! 40 particles, 2 m long, 0.2 kg, pinned at one end, released horizontal under gravity, 4 s at
//! dt = 1/60 s. The XPBD rope keeps its length by projecting every link back to its rest length
//! (`--substeps` substeps of `--iterations` sweeps per frame); the spring rope (k = 10⁴ N/m per
//! link, so ω·dt ≈ 100) is stable only because implicit Euler is; the rod rope keeps its length
//! to the tolerance (`--rtol`, adaptive steps, saved at the frames).
//!
//! `cargo run --release --example rope` writes `out/rope/rope.csv`
//! (`method,step,t,tip_x,tip_y,stretch,energy`), `out/rope/rope.png` (the two ropes at several
//! times) and `out/rope/energy.png` (energy and stretch over time).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;
use odyn::output::{number, write_table};
use odyn::particles::Spring;
use odyn::plot::{Chart, Series, View, views};
use odyn::prelude::*;
use odyn::xpbd::{Constraint, Xpbd, XpbdOptions};
use scenes::RodRope;

/// A rope of stiff springs under gravity.
#[system(integrator = ImplicitEuler, dt = 1.0 / 60.0)]
pub struct Rope {
    /// Positions (m).
    #[position]
    pub x: Vec<Vector2<f64>>,
    /// Velocities (m/s).
    #[velocity]
    pub v: Vec<Vector2<f64>>,
    /// Masses (kg).
    #[mass]
    pub mass: Vec<f64>,
    /// The fixed end.
    #[pinned]
    pub pinned: Vec<usize>,
    /// One spring per link.
    pub links: Vec<Spring>,
    /// Gravitational acceleration (m/s²).
    pub g: f64,
}

#[system]
impl Rope {
    /// Hooke's law plus damping along the link.
    #[pair(links)]
    fn spring(
        &self,
        s: &Spring,
        xa: Vector2<f64>,
        xb: Vector2<f64>,
        va: Vector2<f64>,
        vb: Vector2<f64>,
    ) -> Vector2<f64> {
        let d = xb - xa;
        let length = d.norm();
        let direction = d / length;
        direction * (s.stiffness * (length - s.rest) + s.damping * (vb - va).dot(&direction))
    }

    /// Weight.
    #[particle]
    fn weight(&self, i: usize, _x: Vector2<f64>) -> Vector2<f64> {
        Vector2::new(0.0, -self.g * self.mass[i])
    }

    /// Spring and gravitational energy.
    fn potential(&self) -> f64 {
        let springs: f64 = self
            .links
            .iter()
            .map(|s| 0.5 * s.stiffness * ((self.x[s.b] - self.x[s.a]).norm() - s.rest).powi(2))
            .sum();
        let gravity: f64 = self
            .x
            .iter()
            .zip(&self.mass)
            .map(|(x, m)| m * self.g * x.y)
            .sum();
        springs + gravity
    }
}

/// A hanging rope: XPBD constraints against implicit Euler with stiff springs.
#[derive(Parser)]
#[command(about)]
struct Cli {
    /// Particles.
    #[arg(long, default_value_t = 40)]
    n: usize,
    /// Spring stiffness of the spring rope (N/m per link).
    #[arg(long, default_value_t = 1e4)]
    k: f64,
    /// XPBD substeps per frame.
    #[arg(long, default_value_t = 20)]
    substeps: u32,
    /// XPBD constraint sweeps per substep.
    #[arg(long, default_value_t = 1)]
    iterations: u32,
    /// Relative tolerance of the rod rope (its absolute tolerance is 1e-2 of it, in m).
    #[arg(long, default_value_t = 1e-6)]
    rtol: f64,
    /// Simulated seconds.
    #[arg(long, default_value_t = 4.0)]
    duration: f64,
    /// Output directory.
    #[arg(long, default_value = "out/rope")]
    out: PathBuf,
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}

const LENGTH: f64 = 2.0;
const MASS: f64 = 0.2;
const G: f64 = 9.81;
const DT: f64 = 1.0 / 60.0;

/// One recorded state of either rope.
struct Frame {
    step: u64,
    t: f64,
    x: Vec<Vector2<f64>>,
    energy: f64,
}

/// The rope as XPBD particles: one rigid (zero-compliance) distance constraint per link,
/// `substeps` substeps of `iterations` sweeps per frame (`odyn::xpbd`).
fn xpbd_rope(n: usize, substeps: u32, iterations: u32, steps: u64) -> odyn::Result<Vec<Frame>> {
    let rest = LENGTH / (n - 1) as f64;
    let m = MASS / n as f64;
    let x: Vec<_> = (0..n).map(|i| Vector2::new(i as f64 * rest, 0.0)).collect();
    let mut rope = Xpbd::new(
        x,
        vec![Vector2::zeros(); n],
        &vec![m; n],
        &[0],
        Vector2::new(0.0, -G),
    )?;
    rope.constraints = (0..n - 1)
        .map(|i| Constraint::Distance {
            ends: [i, i + 1],
            rest,
            compliance: 0.0,
        })
        .collect();
    rope.options = XpbdOptions {
        substeps,
        iterations,
    };
    let energy = |rope: &Xpbd<2>| -> f64 {
        rope.x
            .iter()
            .zip(&rope.v)
            .map(|(x, v)| 0.5 * m * v.norm_squared() + m * G * x.y)
            .sum()
    };
    let mut frames = vec![Frame {
        step: 0,
        t: 0.0,
        energy: energy(&rope),
        x: rope.x.clone(),
    }];
    for step in 1..=steps {
        rope.step(DT)?;
        frames.push(Frame {
            step,
            t: step as f64 * DT,
            energy: energy(&rope),
            x: rope.x.clone(),
        });
    }
    Ok(frames)
}

/// The rope as rigid rods (`scenes::RodRope`: a DAE whose rod forces are algebraic) under
/// Rodas5P at `rtol`, saved at every frame; the pinned end prepended to each frame's positions.
fn rod_rope(n: usize, rtol: f64, duration: f64) -> odyn::Result<(Vec<Frame>, odyn::Stats)> {
    let rest = LENGTH / (n - 1) as f64;
    let rope = RodRope::straight(n - 1, MASS / n as f64, rest, std::f64::consts::FRAC_PI_2)?;
    let steps = (duration / DT).round() as u64;
    let frames: Vec<f64> = (0..=steps).map(|i| i as f64 * DT).collect();
    let run = rope
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(rtol, 1e-2 * rtol)
        .save_at(&frames)
        .duration(duration)
        .run()?;
    let frames = run
        .samples
        .iter()
        .enumerate()
        .map(|(step, s)| {
            let (x, y) = (s.state.field(0), s.state.field(1));
            let mut points = vec![Vector2::zeros()];
            points.extend(x.iter().zip(y).map(|(&x, &y)| Vector2::new(x, y)));
            Frame {
                step: step as u64,
                t: s.t,
                x: points,
                energy: rope.energy(&s.state),
            }
        })
        .collect();
    Ok((frames, run.stats))
}

fn rope(n: usize, k: f64) -> Rope {
    let x: Vec<_> = (0..n)
        .map(|i| Vector2::new(i as f64 * LENGTH / (n - 1) as f64, 0.0))
        .collect();
    Rope {
        // Critical damping of one link's stretch mode would be 2√(k·m/2); a small fraction of it.
        links: (0..n - 1)
            .map(|i| Spring::at_rest(&x, i, i + 1, k, 0.05 * (k * MASS / n as f64).sqrt()))
            .collect(),
        v: vec![Vector2::zeros(); n],
        mass: vec![MASS / n as f64; n],
        pinned: vec![0],
        g: G,
        x,
    }
}

/// Largest relative link stretch |d|/L − 1.
fn stretch(x: &[Vector2<f64>], rest: f64) -> f64 {
    x.windows(2)
        .map(|w| ((w[1] - w[0]).norm() / rest - 1.0).abs())
        .fold(0.0, f64::max)
}

fn run(cli: Cli) -> odyn::Result<()> {
    if cli.n < 2 {
        return Err(Error::InvalidInput {
            field: "--n".into(),
            reason: format!("a rope needs at least 2 particles, got {}", cli.n),
        });
    }
    let n = cli.n;
    let rest = LENGTH / (n - 1) as f64;
    let steps = (cli.duration / DT).round() as u64;
    println!(
        "rope: {n} particles, {LENGTH} m, {MASS} kg, one end pinned, dt = 1/60 s, {steps} steps"
    );

    let verlet = xpbd_rope(n, cli.substeps, cli.iterations, steps)?;
    let model = rope(n, cli.k);
    let omega = 2.0 * (cli.k / model.mass[0]).sqrt();
    let run = model.simulate().duration(cli.duration).run()?;
    let springs: Vec<Frame> = run
        .samples
        .iter()
        .map(|s| Frame {
            step: s.step,
            t: s.t,
            x: s.state.positions().to_vec(),
            energy: s.energy.unwrap_or(f64::NAN),
        })
        .collect();
    println!(
        "  XPBD, {} substeps × {} sweeps: max stretch {:.2e}, energy {:.4} -> {:.4} J",
        cli.substeps,
        cli.iterations,
        verlet
            .iter()
            .map(|f| stretch(&f.x, rest))
            .fold(0.0, f64::max),
        verlet[0].energy,
        verlet[verlet.len() - 1].energy,
    );
    println!(
        "  stiff springs (k = {:e}, omega*dt = {:.0}), implicit Euler: max stretch {:.2e}, \
         energy {:.4} -> {:.4} J",
        cli.k,
        omega * DT,
        springs
            .iter()
            .map(|f| stretch(&f.x, rest))
            .fold(0.0, f64::max),
        springs[0].energy,
        springs[springs.len() - 1].energy,
    );
    let started = std::time::Instant::now();
    let (rods, stats) = rod_rope(n, cli.rtol, cli.duration)?;
    println!(
        "  rigid rods (DAE), Rodas5P at rtol {:e}: max stretch {:.2e}, energy {:.4} -> {:.4} J \
         ({} steps, {:.2} s)",
        cli.rtol,
        rods.iter().map(|f| stretch(&f.x, rest)).fold(0.0, f64::max),
        rods[0].energy,
        rods[rods.len() - 1].energy,
        stats.steps,
        started.elapsed().as_secs_f64(),
    );
    let explicit = model
        .simulate()
        .integrator(Method::VelocityVerlet)
        .duration(cli.duration)
        .run_partial()?;
    if let (_, Some(error)) = &explicit {
        println!("  the same spring rope with velocity Verlet: {error}");
    }

    std::fs::create_dir_all(&cli.out).map_err(|source| Error::Io {
        path: cli.out.clone(),
        source,
    })?;
    let ropes = [
        ("xpbd_constraints", &verlet),
        ("implicit_springs", &springs),
        ("dae_rods", &rods),
    ];
    let mut rows = Vec::new();
    for (name, frames) in ropes {
        for f in frames.iter() {
            let tip = f.x[n - 1];
            rows.push(vec![
                name.to_owned(),
                f.step.to_string(),
                number(f.t),
                number(tip.x),
                number(tip.y),
                number(stretch(&f.x, rest)),
                number(f.energy),
            ]);
        }
    }
    write_table(
        cli.out.join("rope.csv"),
        &["method", "step", "t", "tip_x", "tip_y", "stretch", "energy"],
        &rows,
    )?;

    // The two ropes at several times, one panel each.
    let times = [0.0, 0.25, 0.5, 0.75, 1.0, 2.0, cli.duration];
    let panel = |title: &str, frames: &[Frame]| {
        let mut segments = Vec::new();
        for &t in &times {
            if let Some(f) = frames.iter().find(|f| f.t >= t - 1e-9) {
                segments.extend(f.x.windows(2).map(|w| [(w[0].x, w[0].y), (w[1].x, w[1].y)]));
            }
        }
        View {
            title: title.into(),
            x_label: "x (m)".into(),
            y_label: "y (m)".into(),
            segments,
            points: vec![(0.0, 0.0)],
            bounds: ((-2.2, 2.2), (-2.3, 0.2)),
            ..View::default()
        }
    };
    views(
        cli.out.join("rope.png"),
        "Rope at t = 0, 0.25, 0.5, 0.75, 1, 2, 4 s (dt = 1/60 s)",
        &[
            panel("rigid links, XPBD", &verlet),
            panel("stiff springs, implicit Euler", &springs),
            panel("rigid rods (DAE), Rodas5P", &rods),
        ],
        (1800, 650),
    )?;
    let series = |label: &str, frames: &[Frame], value: &dyn Fn(&Frame) -> f64| {
        Series::line(label, frames.iter().map(|f| (f.t, value(f))).collect())
    };
    Chart {
        title: "Rope energy (J): XPBD, implicit Euler, rods as a DAE".into(),
        x_label: "t (s)".into(),
        y_label: "kinetic + potential energy (J)".into(),
        series: vec![
            series("rigid links, XPBD", &verlet, &|f| f.energy),
            series("stiff springs, implicit Euler", &springs, &|f| f.energy),
            series("rigid rods (DAE), Rodas5P", &rods, &|f| f.energy),
        ],
        ..Chart::default()
    }
    .write(cli.out.join("energy.png"), (1000, 600))?;
    println!("wrote {}/rope.csv, rope.png, energy.png", cli.out.display());
    Ok(())
}
