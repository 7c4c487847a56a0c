//! Stiff cloth at a frame-sized step (Baraff & Witkin, "Large Steps in Cloth Simulation", 1998).
//!
//! An N×N cloth (default 32×32) of side 1 m and mass 0.5 kg, joined by structural, shear and
//! bend springs of stiffness k (default 10⁴ N/m), starts horizontal, pinned at its two top
//! corners, and falls under gravity for 5 s at dt = 1/60 s. Every method runs at that dt: the
//! explicit ones diverge within a few steps (a typed error naming the step), implicit Euler with
//! the sparse Newton solve stays stable, both as full Newton and as the one-step linearized form.
//! Beside them the same cloth runs as XPBD particles (`odyn::xpbd`), every spring a distance
//! constraint of compliance 1/k, 40 substeps a frame.
//!
//! `cargo run --release --example cloth [-- --n 64 --k 1e6]` writes `out/cloth/energy.csv`
//! (`method,step,t,kinetic,potential,energy`), `out/cloth/energy.png`, and the cloth seen from
//! the front and the side, `out/cloth/frame_*.png`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use indicatif::{ProgressBar, ProgressStyle};
use odyn::output::{number, write_table};
use odyn::particles::{ParticleState, ParticleSystem};
use odyn::plot::{Chart, Series, View, views};
use odyn::prelude::*;
// The cloth: its model and the sheet that builds it (`scenes/src/cloth.rs`).
use odyn::xpbd::Xpbd;
use odyn::{NewtonOptions, ParticleSolve, Sample};
use scenes::{Cloth, Sheet};

/// Stiff cloth: explicit methods against implicit Euler at dt = 1/60.
#[derive(Parser)]
#[command(about)]
struct Cli {
    /// Particles per side (2 to 128).
    #[arg(long, default_value_t = 32)]
    n: usize,
    /// Spring stiffness k (N/m).
    #[arg(long, default_value_t = 1e4)]
    k: f64,
    /// Spring damping c along each spring (N·s/m).
    #[arg(long, default_value_t = 0.02)]
    damping: f64,
    /// Simulated seconds.
    #[arg(long, default_value_t = 5.0)]
    duration: f64,
    /// XPBD substeps per frame (one constraint sweep each).
    #[arg(long, default_value_t = 40)]
    xpbd_substeps: u32,
    /// Output directory.
    #[arg(long, default_value = "out/cloth")]
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

/// The cloth and which of its springs are structural (drawn in the frames): 0.5 kg, drag 0.02
/// N·s/m in all, starting horizontal (`scenes/src/cloth.rs` builds it).
fn cloth(n: usize, k: f64, damping: f64) -> (Cloth, Vec<usize>) {
    let sheet = Sheet {
        stiffness: k,
        damping,
        ..Sheet::falling(n)
    };
    sheet.build()
}

/// One run: a label, its recorded states, and the failure that ended it early, if any.
struct Run {
    name: String,
    label: String,
    samples: Vec<Sample<ParticleState<3>>>,
    failure: Option<Error>,
}

fn run(cli: Cli) -> odyn::Result<()> {
    if !(2..=128).contains(&cli.n) {
        return Err(Error::InvalidInput {
            field: "--n".into(),
            reason: format!("must be between 2 and 128, got {}", cli.n),
        });
    }
    let n = cli.n;
    let (cloth, structural) = cloth(n, cli.k, cli.damping);
    let mass = cloth.mass[0];
    println!(
        "cloth {n}x{n}: {} particles, {} springs, k = {:e} N/m, particle mass {mass:.3e} kg, \
         dt = 1/60 s, {} s",
        n * n,
        cloth.springs.len(),
        cli.k,
        cli.duration
    );
    println!(
        "  stiffest spring mode: omega ~ 2*sqrt(k/m) = {:.0} rad/s, omega*dt = {:.0} \
         (explicit methods need omega*dt < 2 to 2.8)",
        2.0 * (cli.k / mass).sqrt(),
        2.0 * (cli.k / mass).sqrt() / 60.0
    );
    // Big cloths record every few steps to keep memory bounded (the CSV says which steps).
    let record_every = if n <= 64 { 1 } else { 5 };
    // Definite Newton matrices: compressed springs' negative stiffness projected away, so
    // Cholesky always applies and the one-step form gains no energy from them (see
    // NewtonOptions::definite).
    let definite = NewtonOptions {
        definite: true,
        particle_solve: ParticleSolve::Newton,
        ..NewtonOptions::default()
    };
    // Full Newton on the exact Jacobian, to 1e-6 relative (micrometres on a metre of cloth).
    let full = NewtonOptions {
        tol: 1e-6,
        particle_solve: ParticleSolve::Newton,
        ..NewtonOptions::default()
    };
    // Every fixed-step method at the frame step; the explicit adaptive ones would only shrink
    // their steps to the stiff springs' stability limit.
    let mut plans: Vec<(String, String, Method, NewtonOptions)> = Method::ALL
        .iter()
        .filter(|m| !m.is_adaptive())
        .map(|&m| {
            let label = match m {
                Method::ImplicitEuler => "implicit Euler, full Newton (tol 1e-6)".to_owned(),
                _ => m.label().to_owned(),
            };
            (m.name().to_owned(), label, m, full)
        })
        .collect();
    plans.push((
        "implicit_euler_linearized".into(),
        "implicit Euler, one Newton step (Baraff–Witkin)".into(),
        Method::ImplicitEuler,
        NewtonOptions {
            linearized: true,
            ..definite
        },
    ));
    // The Rosenbrock methods at the frame step: one sparse factorization per step on the same
    // Jacobian, no Newton iteration. (Adaptive at rtol 1e-3, Rosenbrock23 needed 16 728 steps,
    // 489 s, for the 5 s: the cloth's fast oscillations set the accuracy-limited step.)
    for method in [Method::Rosenbrock23, Method::Rodas5P] {
        plans.push((
            method.name().to_owned(),
            format!("{} (fixed dt)", method.label()),
            method,
            full,
        ));
    }
    let mut runs = Vec::new();
    for (name, label, method, newton) in plans {
        let bar = ProgressBar::new(1000);
        bar.set_style(
            ProgressStyle::with_template("  {msg:<48} [{bar:30}] {percent:>3}% {elapsed}")
                .unwrap_or_else(|_| ProgressStyle::default_bar())
                .progress_chars("=> "),
        );
        bar.set_message(label.clone());
        let report = |p: &odyn::Progress| bar.set_position((1000.0 * p.fraction()) as u64);
        let started = Instant::now();
        let simulation = cloth
            .simulate()
            .integrator(method)
            .newton(newton)
            .duration(cli.duration)
            .record_every(record_every)
            .progress(&report);
        let simulation = if method.is_adaptive() {
            simulation.dt(1.0 / 60.0)
        } else {
            simulation
        };
        let result = simulation.run_partial();
        bar.finish_and_clear();
        let (trajectory, failure) = match result {
            Ok(run) => run,
            // Position Verlet cannot pass velocities to the damping: reported, not fatal.
            Err(error @ Error::Unsupported { .. }) => {
                println!("  {label:<48} not run: {error}");
                continue;
            }
            Err(error) => return Err(error),
        };
        let seconds = started.elapsed().as_secs_f64();
        match &failure {
            Some(error) => println!("  {label:<48} {error}"),
            None => {
                let last = &trajectory.samples[trajectory.samples.len() - 1];
                println!(
                    "  {label:<48} finished: {} steps in {seconds:.2} s ({:.1} ms/step, {} \
                     factorizations), kinetic energy at {} s: {:.3e} J",
                    trajectory.steps(),
                    1e3 * seconds / trajectory.steps().max(1) as f64,
                    trajectory.stats.factorizations,
                    cli.duration,
                    cloth.kinetic_energy(&last.state)
                );
            }
        }
        runs.push(Run {
            name,
            label,
            samples: trajectory.samples,
            failure,
        });
    }
    runs.push(xpbd(&cloth, cli.xpbd_substeps, cli.duration, record_every)?);
    std::fs::create_dir_all(&cli.out).map_err(|source| Error::Io {
        path: cli.out.clone(),
        source,
    })?;
    write_energy(&cli.out, &cloth, &runs)?;
    let implicit = runs
        .iter()
        .find(|r| r.name == Method::ImplicitEuler.name() && r.failure.is_none())
        .or_else(|| runs.iter().find(|r| r.failure.is_none()));
    if let Some(run) = implicit {
        write_frames(&cli.out, &cloth, &structural, run)?;
    }
    println!(
        "wrote {}/energy.{{csv,png}} and frame_*.png",
        cli.out.display()
    );
    Ok(())
}

/// The same cloth as XPBD particles (`Cloth::as_xpbd`: every spring a distance constraint of
/// compliance 1/k, the same pins and gravity, no air drag), `substeps` substeps of one sweep per
/// 1/60 s frame.
fn xpbd(cloth: &Cloth, substeps: u32, duration: f64, record_every: u64) -> odyn::Result<Run> {
    let mut particles = cloth.as_xpbd(substeps)?;
    let dt = 1.0 / 60.0;
    let steps = (duration / dt).round() as u64;
    let sample = |step: u64, particles: &Xpbd<3>| -> odyn::Result<Sample<ParticleState<3>>> {
        Ok(Sample {
            step,
            t: step as f64 * dt,
            state: ParticleState::new(&particles.x, &particles.v)?,
            energy: None,
        })
    };
    let mut samples = vec![sample(0, &particles)?];
    let started = Instant::now();
    for step in 1..=steps {
        particles.step(dt)?;
        if step % record_every == 0 {
            samples.push(sample(step, &particles)?);
        }
    }
    let seconds = started.elapsed().as_secs_f64();
    let label = format!("XPBD, {substeps} substeps (compliance 1/k)");
    let last = &samples[samples.len() - 1];
    println!(
        "  {label:<48} finished: {steps} steps in {seconds:.2} s ({:.1} ms/step), max stretch \
         {:.2e}, kinetic energy at {duration} s: {:.3e} J",
        1e3 * seconds / steps as f64,
        particles.max_stretch(),
        cloth.kinetic_energy(&last.state)
    );
    Ok(Run {
        name: "xpbd".into(),
        label,
        samples,
        failure: None,
    })
}

fn write_energy(dir: &Path, cloth: &Cloth, runs: &[Run]) -> odyn::Result<()> {
    let mut rows = Vec::new();
    let mut series = Vec::new();
    for run in runs {
        let mut points = Vec::new();
        for s in &run.samples {
            let kinetic = cloth.kinetic_energy(&s.state);
            let potential = cloth.potential_energy(&s.state).unwrap_or(f64::NAN);
            rows.push(vec![
                run.name.clone(),
                s.step.to_string(),
                number(s.t),
                number(kinetic),
                number(potential),
                number(kinetic + potential),
            ]);
            points.push((s.t, kinetic));
        }
        let label = match &run.failure {
            Some(Error::Diverged { step, .. }) => {
                format!("{} (diverged at step {step})", run.label)
            }
            Some(_) => format!("{} (failed)", run.label),
            None => run.label.clone(),
        };
        series.push(Series::line(label, points));
    }
    write_table(
        dir.join("energy.csv"),
        &["method", "step", "t", "kinetic", "potential", "energy"],
        &rows,
    )?;
    Chart {
        title: "Stiff cloth at dt = 1/60 s: kinetic energy".into(),
        x_label: "t (s)".into(),
        y_label: "kinetic energy (J)".into(),
        log_y: true,
        series,
        ..Chart::default()
    }
    .write(dir.join("energy.png"), (1100, 700))
}

fn write_frames(dir: &Path, cloth: &Cloth, structural: &[usize], run: &Run) -> odyn::Result<()> {
    let samples = &run.samples;
    // One region for every frame, so the motion shows.
    let (mut lo, mut hi) = (
        Vector3::repeat(f64::INFINITY),
        Vector3::repeat(f64::NEG_INFINITY),
    );
    for s in samples {
        for p in s.state.positions() {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
    }
    let margin = 0.05 * (hi - lo).max();
    let range = |axis: usize| (lo[axis] - margin, hi[axis] + margin);
    let end = samples[samples.len() - 1].t;
    let times = [0.0, 0.25, 0.5, 1.0, 2.0, end];
    for (k, &t) in times.iter().enumerate() {
        let Some(sample) = samples.iter().find(|s| s.t >= t - 1e-9) else {
            continue;
        };
        let x = sample.state.positions();
        let view = |title: &str, h: usize, h_label: &str| View {
            title: title.into(),
            x_label: h_label.into(),
            y_label: "y (m)".into(),
            segments: structural
                .iter()
                .map(|&i| {
                    let s = &cloth.springs[i];
                    [(x[s.a][h], x[s.a].y), (x[s.b][h], x[s.b].y)]
                })
                .collect(),
            points: cloth.pinned.iter().map(|&p| (x[p][h], x[p].y)).collect(),
            bounds: (range(h), range(1)),
            ..View::default()
        };
        views(
            dir.join(format!("frame_{k}.png")),
            &format!("{}, t = {:.2} s", run.label, sample.t),
            &[
                view("front (x–y)", 0, "x (m)"),
                view("side (z–y)", 2, "z (m)"),
            ],
            (1200, 620),
        )?;
    }
    Ok(())
}
