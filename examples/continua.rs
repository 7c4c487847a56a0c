//! The continuum methods side by side on Martin & Moyce's dam break (a = 0.2 m, to T = 3.4),
//! at a common resolution: 40 particles across the column for SPH, 20 cells across it (four
//! particles a cell: the same 3 200 particles) for FLIP, APIC and MPM, and Stable Fluids' step
//! on the same 100 × 60 grid (it has no free surface, so no front).
//!
//! `cargo run --release --example continua` prints, for each: steps to T = 3.33, milliseconds a
//! step and per simulated second, and the front's mean and largest difference from the data
//! (`scenes::MARTIN_MOYCE`); and writes `out/continua/table.csv`. `benches/continua.rs` times
//! one step of each with divan.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use odyn::fluids::{FluidOptions, StableFluids};
use odyn::hybrid::Transfer;
use odyn::output::{number, write_table};
// The dam breaks and the data (`scenes/src/fluids.rs`, `scenes/src/hybrid.rs`).
use scenes::MARTIN_MOYCE;
use scenes::hybrid::{mpm_dam_break, mpm_front};

/// The continuum methods on one dam break.
#[derive(Parser)]
#[command(about)]
struct Cli {
    /// Output directory.
    #[arg(long, default_value = "out/continua")]
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

const A: f64 = 0.2;

/// One method's run: its name, steps, seconds of computing, and front errors at the data's
/// times.
struct Row {
    name: &'static str,
    steps: u64,
    seconds: f64,
    errors: Vec<f64>,
}

/// Runs `step` (which returns the step's dt) to each of the data's times and reads `front`.
fn race(
    name: &'static str,
    mut step: impl FnMut() -> odyn::Result<f64>,
    front: impl Fn() -> f64,
) -> odyn::Result<Row> {
    let scale = (2.0 * 9.81 / A).sqrt();
    let (mut t, mut steps, mut seconds) = (0.0, 0, 0.0);
    let mut errors = Vec::new();
    for &(time, z) in &MARTIN_MOYCE {
        let clock = Instant::now();
        while t * scale < time {
            t += step()?;
            steps += 1;
        }
        seconds += clock.elapsed().as_secs_f64();
        errors.push(front() / A / z - 1.0);
    }
    Ok(Row {
        name,
        steps,
        seconds,
        errors,
    })
}

fn run(cli: Cli) -> odyn::Result<()> {
    let mut rows = Vec::new();
    let sph = std::cell::RefCell::new(scenes::dam_break(A, 40)?);
    rows.push(race(
        "SPH (40 particles across)",
        || {
            let mut sph = sph.borrow_mut();
            let dt = sph.stable_dt();
            sph.step(dt).map(|()| dt)
        },
        || sph.borrow().front(),
    )?);
    for (name, transfer) in [
        (
            "FLIP 0.95 (20 cells across)",
            Transfer::Blend { flip: 0.95 },
        ),
        ("APIC (20 cells across)", Transfer::Apic),
    ] {
        let flip = std::cell::RefCell::new(scenes::flip_dam_break(A, 20, transfer)?);
        rows.push(race(
            name,
            || {
                let mut flip = flip.borrow_mut();
                let dt = flip.stable_dt();
                flip.step(dt).map(|()| dt)
            },
            || flip.borrow().front(),
        )?);
    }
    let mpm = std::cell::RefCell::new(mpm_dam_break(A, 20)?);
    rows.push(race(
        "MLS-MPM water (20 cells across)",
        || {
            let mut mpm = mpm.borrow_mut();
            let dt = mpm.stable_dt();
            mpm.step(dt).map(|()| dt)
        },
        || mpm_front(&mpm.borrow()),
    )?);
    let t_last = MARTIN_MOYCE[MARTIN_MOYCE.len() - 1].0 / (2.0 * 9.81 / A).sqrt();
    println!(
        "Dam break (a = {A} m) to T = 3.33, t = {t_last:.3} s; front against Martin & Moyce's \
         15 points"
    );
    println!(
        "  {:32} {:>6} {:>9} {:>12} {:>9} {:>9}",
        "method", "steps", "ms/step", "s/sim. s", "mean", "largest"
    );
    let mut table = Vec::new();
    for row in &rows {
        let mean = row.errors.iter().sum::<f64>() / row.errors.len() as f64;
        let largest = row.errors.iter().fold(0.0f64, |m, e| m.max(e.abs()));
        let per_step = 1e3 * row.seconds / row.steps as f64;
        let per_second = row.seconds / t_last;
        println!(
            "  {:32} {:>6} {:>9.3} {:>12.2} {:>+8.1}% {:>8.1}%",
            row.name,
            row.steps,
            per_step,
            per_second,
            100.0 * mean,
            100.0 * largest
        );
        table.push(vec![
            row.name.to_owned(),
            row.steps.to_string(),
            number(per_step),
            number(per_second),
            number(mean),
            number(largest),
        ]);
    }
    let (nx, ny, h) = (100, 60, A / 20.0);
    let mut smoke = StableFluids::new(FluidOptions {
        nx,
        ny,
        cell: h,
        viscosity: 0.0,
        buoyancy: 4.0,
    })?;
    let clock = Instant::now();
    for _ in 0..100 {
        for i in 45..55 {
            smoke.density[i + 2 * nx] = 1.0;
        }
        smoke.step(0.5 * h)?;
    }
    let per_step = 10.0 * clock.elapsed().as_secs_f64();
    println!(
        "  {:32} {:>6} {per_step:>9.3}   (a smoke plume, no free surface)",
        "Stable Fluids (100 × 60 cells)", ""
    );
    table.push(vec![
        "Stable Fluids (100 × 60 cells)".to_owned(),
        String::new(),
        number(per_step),
        String::new(),
        String::new(),
        String::new(),
    ]);
    write_table(
        cli.out.join("table.csv"),
        &[
            "method",
            "steps",
            "ms per step",
            "s per simulated s",
            "mean front error",
            "largest",
        ],
        &table,
    )?;
    println!("wrote {}/", cli.out.display());
    Ok(())
}
