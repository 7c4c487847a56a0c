//! A 2-D dam break with weakly compressible SPH (`odyn::sph`), against Martin & Moyce (1952).
//!
//! A water column a wide and 2a high (a = 0.2 m, n² = 2 in Martin & Moyce's notation) stands in
//! the corner of a box 5a wide; at t = 0 it collapses. Martin & Moyce measured the surge front
//! z(t) along the floor; in their dimensionless variables Z = z/a and T = t·√(2g/a) the data for
//! n² = 2 are (J. C. Martin & W. J. Moyce, "An experimental study of the collapse of liquid
//! columns on a rigid horizontal plane", Phil. Trans. R. Soc. Lond. A 244 (1952) 312, Table 2,
//! as tabulated in the Lethe project's dam-break post-processing):
//!
//! T = 0.41 0.84 1.19 1.43 1.63 1.83 1.98 2.20 2.32 2.51 2.65 2.83 2.98 3.11 3.33,
//! Z = 1.11 1.22 1.44 1.67 1.89 2.11 2.33 2.56 2.78 3.00 3.22 3.44 3.67 3.89 4.11.
//!
//! `cargo run --release --example sph [-- --resolution 40]` (particles across the column)
//! writes under `out/sph/`: `front.csv` and `front.png` (Z against T beside the data),
//! `frame_*.png` and `dam_break.gif`, and prints the cost per step.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use odyn::output::{number, write_table};
use odyn::plot::{Chart, Frame, Series, View, animation, views};
use odyn::sph::Sph;
// The dam break, written once for the examples, tests and benches (`scenes/src/fluids.rs`).
use scenes::dam_break;

/// Martin & Moyce (1952), n² = 2: (T, Z).
const MARTIN_MOYCE: [(f64, f64); 15] = [
    (0.41, 1.11),
    (0.84, 1.22),
    (1.19, 1.44),
    (1.43, 1.67),
    (1.63, 1.89),
    (1.83, 2.11),
    (1.98, 2.33),
    (2.20, 2.56),
    (2.32, 2.78),
    (2.51, 3.00),
    (2.65, 3.22),
    (2.83, 3.44),
    (2.98, 3.67),
    (3.11, 3.89),
    (3.33, 4.11),
];

/// A dam break with SPH.
#[derive(Parser)]
#[command(about)]
struct Cli {
    /// Particles across the column's width a (its height gets twice as many).
    #[arg(long, default_value_t = 40)]
    resolution: usize,
    /// Output directory.
    #[arg(long, default_value = "out/sph")]
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

fn run(cli: Cli) -> odyn::Result<()> {
    let a = 0.2;
    let g = 9.81;
    let mut sph = dam_break(a, cli.resolution)?;
    let scale = (2.0 * g / a).sqrt();
    let t_end = 3.4 / scale;
    let mass = sph.fluid_mass();
    println!(
        "Dam break: column {a} m × {} m, {} fluid and {} wall particles, c₀ = {:.1} m/s, to \
         T = 3.4 (t = {t_end:.3} s)",
        2.0 * a,
        sph.x.len(),
        sph.walls().len(),
        sph.options().sound_speed
    );
    let (mut t, mut steps) = (0.0, 0u64);
    let mut front = vec![(0.0, sph.front() / a)];
    let mut frames = Vec::new();
    let mut next_frame = 0.0;
    let started = Instant::now();
    while t < t_end {
        if t >= next_frame {
            frames.push((t, sph.x.clone()));
            next_frame += 0.1 / scale;
        }
        let dt = sph.stable_dt().min(t_end - t);
        sph.step(dt)?;
        t += dt;
        steps += 1;
        front.push((t * scale, sph.front() / a));
    }
    frames.push((t, sph.x.clone()));
    let seconds = started.elapsed().as_secs_f64();
    let particles = sph.x.len() + sph.walls().len();
    println!(
        "  {steps} steps in {seconds:.2} s: {:.3} ms a step, {:.2} µs per particle-step; fluid \
         mass {mass} kg before and {} kg after",
        1e3 * seconds / steps as f64,
        1e6 * seconds / (steps as f64 * particles as f64),
        sph.fluid_mass()
    );
    let at = |tt: f64| {
        front
            .iter()
            .find(|(t, _)| *t >= tt)
            .map_or(f64::NAN, |p| p.1)
    };
    let errors: Vec<f64> = MARTIN_MOYCE
        .iter()
        .map(|&(tt, z)| (at(tt) - z) / z)
        .collect();
    println!("  surge front Z = z/a against Martin & Moyce (T: SPH / experiment):");
    for (&(tt, z), e) in MARTIN_MOYCE.iter().zip(&errors) {
        println!(
            "    T = {tt:.2}: {:.2} / {z:.2} ({:+.1} %)",
            at(tt),
            100.0 * e
        );
    }
    let mean = errors.iter().sum::<f64>() / errors.len() as f64;
    println!("  mean relative difference {:+.1} %", 100.0 * mean);
    write_table(
        cli.out.join("front.csv"),
        &["T", "Z"],
        &front
            .iter()
            .step_by(10)
            .map(|&(t, z)| vec![number(t), number(z)])
            .collect::<Vec<_>>(),
    )?;
    Chart {
        title: format!(
            "Dam break, {} particles across a: surge front",
            cli.resolution
        ),
        x_label: "T = t·√(2g/a)".into(),
        y_label: "Z = z/a".into(),
        series: vec![
            Series::line("SPH", front),
            Series::markers("Martin & Moyce (1952), n² = 2", MARTIN_MOYCE.to_vec()),
        ],
        ..Chart::default()
    }
    .write(cli.out.join("front.png"), (900, 600))?;
    write_frames(&cli.out, &sph, a, scale, &frames)?;
    println!("wrote {}/", cli.out.display());
    Ok(())
}

fn write_frames(
    dir: &Path,
    sph: &Sph,
    a: f64,
    scale: f64,
    frames: &[(f64, Vec<odyn::nalgebra::Vector2<f64>>)],
) -> odyn::Result<()> {
    let view = |x: &[odyn::nalgebra::Vector2<f64>]| View {
        title: "fluid (red) and wall particles".into(),
        x_label: "x (m)".into(),
        y_label: "y (m)".into(),
        segments: sph
            .walls()
            .iter()
            .map(|w| [(w.x, w.y), (w.x + 1e-4, w.y)])
            .collect(),
        points: x.iter().map(|p| (p.x, p.y)).collect(),
        bounds: ((-0.02, 5.0 * a + 0.02), (-0.02, 2.0 * a + 0.02)),
        ..View::default()
    };
    for (k, (t, x)) in frames.iter().enumerate().step_by(10) {
        views(
            dir.join(format!("frame_{k}.png")),
            &format!("Dam break, T = {:.1}", t * scale),
            &[view(x)],
            (1000, 480),
        )?;
    }
    let animated: Vec<Frame> = frames
        .iter()
        .map(|(t, x)| Frame {
            title: format!("T = {:.1}", t * scale),
            views: vec![view(x)],
        })
        .collect();
    animation(dir.join("dam_break.gif"), &animated, (640, 320), 80)
}
