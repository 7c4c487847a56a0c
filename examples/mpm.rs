//! Jelly, water and snow falling together in a box, by the moving least squares material point
//! method (`odyn::hybrid::mpm`), after the MLS-MPM paper's 99-line program.
//!
//! A block of water (weakly compressible, K = 4·10⁵ Pa) stands on the left, a jelly block
//! (fixed-corotated, E = 3·10⁵ Pa, ν = 0.2) falls onto it, a block of Stomakhin's reference snow
//! falls on the right (`scenes::hybrid::jelly_water_snow`).
//!
//! `cargo run --release --example mpm [-- --grid 128 --seconds 2]` writes under `out/mpm/`:
//! `energy.csv` (kinetic, gravitational, strain and total energy, momentum and angular
//! momentum, every 1/100 s), `energy.png`, `frame_*.png` (every 0.5 s) and `mpm.gif`, and
//! prints the cost per step.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use odyn::hybrid::mpm::{Material, Mpm};
use odyn::nalgebra::Vector2;
use odyn::output::{number, write_table};
use odyn::plot::{Chart, Particles, Series, particle_animation, particles};
// The scene (`scenes/src/hybrid.rs`).
use scenes::hybrid::jelly_water_snow;

/// Jelly, water and snow by MLS-MPM.
#[derive(Parser)]
#[command(about)]
struct Cli {
    /// Grid nodes a side of the unit box.
    #[arg(long, default_value_t = 128)]
    grid: usize,
    /// Simulated seconds.
    #[arg(long, default_value_t = 2.0)]
    seconds: f64,
    /// Output directory.
    #[arg(long, default_value = "out/mpm")]
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
    let (mut mpm, _) = jelly_water_snow(cli.grid)?;
    println!(
        "Jelly, water and snow: {} particles on {}² nodes, to t = {} s",
        mpm.x.len(),
        cli.grid,
        cli.seconds
    );
    let centre = Vector2::new(0.5, 0.5);
    let mut trace = vec![measure(&mpm, 0.0, centre)];
    let mut pictures = vec![picture(&mpm, 0.0)];
    let (mut t, mut next_trace, mut next_frame) = (0.0, 0.01, 1.0 / 25.0);
    let started = Instant::now();
    while t < cli.seconds {
        // The stiffest particle sets the step: compacted snow hardens as it goes.
        let dt = mpm.stable_dt().min(cli.seconds - t);
        mpm.step(dt)?;
        t += dt;
        if t >= next_trace {
            trace.push(measure(&mpm, t, centre));
            next_trace += 0.01;
        }
        if t >= next_frame {
            pictures.push(picture(&mpm, t));
            next_frame += 1.0 / 25.0;
        }
    }
    let seconds = started.elapsed().as_secs_f64();
    let steps = mpm.steps().0;
    println!(
        "  {steps} steps in {seconds:.2} s: {:.3} ms a step, {:.1} ns per particle-step",
        1e3 * seconds / steps as f64,
        1e9 * seconds / (steps as f64 * mpm.x.len() as f64)
    );
    let (first, last) = (&trace[0], &trace[trace.len() - 1]);
    println!(
        "  energy {:.4} J/m at rest, {:.4} J/m at the end (water, snow and the jelly's damping \
         by the transfers dissipate); mass {} kg/m throughout",
        first[4],
        last[4],
        mpm.mass()
    );
    let header = [
        "t", "kinetic", "gravity", "strain", "total", "px", "py", "L",
    ];
    let rows: Vec<Vec<String>> = trace
        .iter()
        .map(|row| row.iter().map(|&x| number(x)).collect())
        .collect();
    write_table(cli.out.join("energy.csv"), &header, &rows)?;
    let series = |k: usize, name: &str| {
        Series::line(name, trace.iter().map(|row| (row[0], row[k])).collect())
    };
    Chart {
        title: "Jelly, water and snow: energy (J per metre of depth)".into(),
        x_label: "t (s)".into(),
        y_label: "energy (J/m)".into(),
        series: vec![
            series(1, "kinetic"),
            series(3, "strain"),
            series(4, "total (with gravity's)"),
        ],
        ..Chart::default()
    }
    .write(cli.out.join("energy.png"), (900, 600))?;
    for (k, picture) in pictures.iter().enumerate().step_by(12) {
        particles(cli.out.join(format!("frame_{k}.png")), picture, (800, 800))?;
    }
    particle_animation(cli.out.join("mpm.gif"), &pictures, (480, 480), 40)?;
    println!("wrote {}/", cli.out.display());
    Ok(())
}

/// t, kinetic, gravitational, strain and total energy, momentum (x, y), angular momentum.
fn measure(mpm: &Mpm, t: f64, centre: Vector2<f64>) -> Vec<f64> {
    let p = mpm.momentum();
    vec![
        t,
        mpm.kinetic_energy(),
        mpm.potential_energy(),
        mpm.strain_energy(),
        mpm.energy(),
        p.x,
        p.y,
        mpm.angular_momentum(centre),
    ]
}

/// The particles by material, over the box.
fn picture(mpm: &Mpm, t: f64) -> Particles {
    let materials = mpm.materials();
    let name = |m: &Material| match m {
        Material::Fluid(_) => "water",
        Material::Elastic(_) => "jelly",
        Material::Snow(_) => "snow",
    };
    let mut groups: Vec<(String, Vec<(f64, f64)>)> = materials
        .iter()
        .map(|m| (name(m).to_owned(), Vec::new()))
        .collect();
    for (p, x) in mpm.x.iter().enumerate() {
        groups[mpm.material_of(p)].1.push((x.x, x.y));
    }
    let side = mpm.options().nx as f64 * mpm.options().cell;
    let wall = mpm.options().wall as f64 * mpm.options().cell;
    let (lo, hi) = (wall, side - wall);
    Particles {
        title: format!("MLS-MPM, t = {t:.2} s"),
        groups,
        radius: 1,
        outline: vec![
            [(lo, hi), (lo, lo)],
            [(lo, lo), (hi, lo)],
            [(hi, lo), (hi, hi)],
        ],
        bounds: ((0.0, side), (0.0, side)),
    }
}
