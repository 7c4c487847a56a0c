//! The material point method's validation figures (`tests/continua/mpm.rs` checks each at a
//! cheaper size): an elastic block's period against the continuum's as the grid refines, a
//! spinning disc's angular momentum under APIC and PIC, and snow that holds beside snow that
//! slumps.
//!
//! `cargo run --release --example mpm_checks` writes under `out/mpm_checks/`: `period.csv`,
//! `period.png`, `spin.csv`, `spin.png` and `snow.png`, and prints every figure.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;
use odyn::hybrid::Transfer;
use odyn::hybrid::mpm::Snow;
use odyn::output::{number, write_table};
use odyn::plot::{Chart, Particles, Series, particles};
// The scenes (`scenes/src/hybrid.rs`).
use scenes::hybrid::{column_height, ringing_block, snow_column, spinning_disc};

/// MPM's validation figures.
#[derive(Parser)]
#[command(about)]
struct Cli {
    /// Output directory.
    #[arg(long, default_value = "out/mpm_checks")]
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
    period(&cli)?;
    spin(&cli)?;
    snow(&cli)?;
    println!("wrote {}/", cli.out.display());
    Ok(())
}

/// The free block's first longitudinal mode against T = 2L/c at 8 to 64 cells across.
fn period(cli: &Cli) -> odyn::Result<()> {
    println!("Ringing block (ν = 0, T = 2L/c = 0.2 s): period error by cells across");
    let mut rows = Vec::new();
    let mut points = Vec::new();
    for cells in [8, 16, 32, 64] {
        let mut block = ringing_block(cells)?;
        let error = block.measure_period()? / block.period - 1.0;
        let order = points
            .last()
            .map(|&(_, e): &(f64, f64)| (e / error.abs()).log2());
        println!(
            "  {cells:3} cells, {:6} particles: {:+.4} %{}",
            block.mpm.x.len(),
            100.0 * error,
            order.map_or(String::new(), |p| format!(", order {p:.2}"))
        );
        rows.push(vec![number(cells as f64), number(error)]);
        points.push((cells as f64, error.abs()));
    }
    write_table(
        cli.out.join("period.csv"),
        &["cells", "relative error"],
        &rows,
    )?;
    let reference: Vec<(f64, f64)> = points
        .iter()
        .map(|&(n, _)| (n, points[0].1 * (points[0].0 / n).powi(2)))
        .collect();
    Chart {
        title: "Elastic block: period error against the continuum's 2L/c".into(),
        x_label: "cells across the block".into(),
        y_label: "|T/T_exact − 1|".into(),
        series: vec![
            Series::markers("MLS-MPM, APIC", points),
            Series::line("second order", reference),
        ],
        log_x: true,
        log_y: true,
        ..Chart::default()
    }
    .write(cli.out.join("period.png"), (900, 600))
}

/// The disc's angular momentum over 10⁴ steps under APIC and PIC.
fn spin(cli: &Cli) -> odyn::Result<()> {
    println!("Spinning elastic disc, 32² grid, 10⁴ steps: L/L₀");
    let mut traces = Vec::new();
    for (name, transfer) in [("APIC", Transfer::Apic), ("PIC", Transfer::PIC)] {
        let (mut mpm, centre) = spinning_disc(32, transfer)?;
        let l0 = mpm.angular_momentum(centre);
        let dt = 0.25 * mpm.stable_dt();
        let mut trace = vec![(0.0, 1.0)];
        for k in 1..=10_000 {
            mpm.step(dt)?;
            if k % 50 == 0 {
                trace.push((k as f64 * dt, mpm.angular_momentum(centre) / l0));
            }
        }
        let worst = trace.iter().fold(0.0f64, |m, p| m.max((p.1 - 1.0).abs()));
        println!(
            "  {name}: {} particles, after {:.2} s L/L₀ = {:.16}, largest departure {worst:.2e}",
            mpm.x.len(),
            10_000.0 * dt,
            trace[trace.len() - 1].1
        );
        traces.push((name, trace));
    }
    let rows: Vec<Vec<String>> = (0..traces[0].1.len())
        .map(|k| {
            vec![
                number(traces[0].1[k].0),
                number(traces[0].1[k].1),
                number(traces[1].1[k].1),
            ]
        })
        .collect();
    write_table(cli.out.join("spin.csv"), &["t", "APIC", "PIC"], &rows)?;
    Chart {
        title: "Spinning elastic disc: angular momentum / initial".into(),
        x_label: "t (s)".into(),
        y_label: "L/L₀".into(),
        series: traces
            .into_iter()
            .map(|(name, trace)| Series::line(name, trace))
            .collect(),
        ..Chart::default()
    }
    .write(cli.out.join("spin.png"), (900, 600))
}

/// Stomakhin's reference snow beside snow with critical strains of 10⁻³, after 1.5 s.
fn snow(cli: &Cli) -> odyn::Result<()> {
    let weak = Snow {
        critical_compression: 1e-3,
        critical_stretch: 1e-3,
        ..Snow::default()
    };
    let mut groups = Vec::new();
    for (name, snow, shift) in [
        ("reference snow", Snow::default(), -0.6),
        ("θc = θs = 10⁻³", weak, 0.6),
    ] {
        let (mut mpm, floor) = snow_column(snow, 32)?;
        let start = column_height(&mpm, floor);
        let mut t = 0.0;
        while t < 1.5 {
            let dt = 0.5 * mpm.stable_dt();
            mpm.step(dt)?;
            t += dt;
        }
        let end = column_height(&mpm, floor);
        let lowest = mpm.volume_ratios().iter().fold(1.0f64, |m, &j| m.min(j));
        println!(
            "Snow column, {name}: height {start:.3} m → {end:.3} m ({:.1} %) after 1.5 s, \
             {} steps; smallest J_P {lowest:.3}",
            100.0 * end / start,
            mpm.steps().0
        );
        groups.push((
            format!("{name}: {:.0} % of its height", 100.0 * end / start),
            mpm.x.iter().map(|x| (x.x + shift, x.y)).collect(),
        ));
    }
    particles(
        cli.out.join("snow.png"),
        &Particles {
            title: "Snow columns 0.5 m high after 1.5 s".into(),
            groups,
            radius: 2,
            outline: vec![[(0.0, 3.0 / 32.0), (3.0, 3.0 / 32.0)]],
            bounds: ((0.3, 2.7), (0.0, 0.9)),
        },
        (1000, 500),
    )
}
