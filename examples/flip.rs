//! A 2-D dam break with a FLIP/APIC liquid (`odyn::hybrid::flip`), against Martin & Moyce (1952).
//!
//! The column of `examples/sph.rs` — a wide, 2a high, a = 0.2 m, in a box 5a wide — collapses;
//! the surge front Z = z/a is compared with Martin & Moyce's data at T = t·√(2g/a)
//! (`scenes::MARTIN_MOYCE`) for three velocity transfers: the 0.95 PIC/FLIP blend, APIC and PIC.
//! The blend's run goes on to t = 4 s with and without the density correction, and the area the
//! liquid fills is traced (FLIP's particles bunch without it).
//!
//! `cargo run --release --example flip [-- --cells 20]` (cells across the column, four particles
//! a cell: 20 gives the 40 particles across of `examples/sph.rs`) writes under `out/flip/`:
//! `front.csv`, `front.png`, `volume.csv`, `volume.png`, `frame_*.png` and `dam_break.gif`, and
//! prints the errors and the cost per step.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use odyn::hybrid::Transfer;
use odyn::hybrid::flip::{Flip, FlipOptions};
use odyn::nalgebra::Vector2;
use odyn::output::{number, write_table};
use odyn::plot::{Chart, Particles, Series, particle_animation, particles};
// The dam break and the data (`scenes/src/fluids.rs`).
use scenes::{MARTIN_MOYCE, flip_dam_break};

/// A FLIP/APIC dam break.
#[derive(Parser)]
#[command(about)]
struct Cli {
    /// Grid cells across the column's width a.
    #[arg(long, default_value_t = 20)]
    cells: usize,
    /// Output directory.
    #[arg(long, default_value = "out/flip")]
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

fn run(cli: Cli) -> odyn::Result<()> {
    let scale = (2.0 * 9.81 / A).sqrt();
    let t_end = 3.4 / scale;
    let transfers = [
        ("FLIP 0.95", Transfer::Blend { flip: 0.95 }),
        ("APIC", Transfer::Apic),
        ("PIC", Transfer::PIC),
    ];
    println!("Dam break, {} cells across a = {A} m:", cli.cells);
    let mut series = Vec::new();
    let mut table = Vec::new();
    let mut blend = None;
    for (name, transfer) in transfers {
        let mut flip = flip_dam_break(A, cli.cells, transfer)?;
        let mut front = vec![(0.0, flip.front() / A)];
        let started = Instant::now();
        let mut t = 0.0;
        while t < t_end {
            let dt = flip.stable_dt().min(t_end - t);
            flip.step(dt)?;
            t += dt;
            front.push((t * scale, flip.front() / A));
        }
        let seconds = started.elapsed().as_secs_f64();
        let (steps, _) = flip.steps();
        let errors: Vec<f64> = MARTIN_MOYCE
            .iter()
            .map(|&(tt, z)| (at(&front, tt) / z) - 1.0)
            .collect();
        let mean = errors.iter().sum::<f64>() / errors.len() as f64;
        let late = errors[7..].iter().fold(0.0f64, |m, e| m.max(e.abs()));
        println!(
            "  {name:9}: {} particles, {steps} steps, {:.2} ms a step ({:.1} CG iterations), \
             mean front error {:+.1} %, largest from T = 2.2 on {:.1} %",
            flip.x.len(),
            1e3 * seconds / steps as f64,
            flip.pressure_work().0 as f64 / steps as f64,
            100.0 * mean,
            100.0 * late
        );
        table.push(errors);
        series.push(Series::line(name, front.clone()));
        if blend.is_none() {
            blend = Some((flip, t));
        }
    }
    println!("  T      data   FLIP 0.95   APIC    PIC  (relative differences)");
    for (k, &(tt, z)) in MARTIN_MOYCE.iter().enumerate() {
        println!(
            "  {tt:.2}   {z:.2}   {:+6.1} %  {:+6.1} %  {:+6.1} %",
            100.0 * table[0][k],
            100.0 * table[1][k],
            100.0 * table[2][k]
        );
    }
    let rows: Vec<Vec<String>> = MARTIN_MOYCE
        .iter()
        .enumerate()
        .map(|(k, &(tt, z))| {
            let mut row = vec![number(tt), number(z)];
            row.extend(table.iter().map(|e| number(z * (1.0 + e[k]))));
            row
        })
        .collect();
    write_table(
        cli.out.join("front.csv"),
        &["T", "Martin & Moyce", "FLIP 0.95", "APIC", "PIC"],
        &rows,
    )?;
    series.push(Series::markers(
        "Martin & Moyce (1952), n² = 2",
        MARTIN_MOYCE.to_vec(),
    ));
    Chart {
        title: format!("FLIP dam break, {} cells across a: surge front", cli.cells),
        x_label: "T = t·√(2g/a)".into(),
        y_label: "Z = z/a".into(),
        series,
        ..Chart::default()
    }
    .write(cli.out.join("front.png"), (900, 600))?;
    let (flip, t) = blend.expect("the blend ran first");
    volume_and_frames(&cli, flip, t)
}

/// Z at time T (the first sample at or after it).
fn at(front: &[(f64, f64)], time: f64) -> f64 {
    front
        .iter()
        .find(|(t, _)| *t >= time)
        .map_or(f64::NAN, |p| p.1)
}

/// The blend's run on to 4 s beside the same run without the density correction: the area
/// each fills, and the corrected run's frames.
fn volume_and_frames(cli: &Cli, mut flip: Flip, mut t: f64) -> odyn::Result<()> {
    let template = flip_dam_break(A, cli.cells, Transfer::Blend { flip: 0.95 })?;
    let mut plain = Flip::new(FlipOptions {
        volume_correction: 0.0,
        ..template.options().clone()
    })?;
    plain.add_particles(&template.x, |_| Vector2::zeros())?;
    let area = plain.filled_area();
    let mut trace = Vec::new();
    let (mut t_plain, mut next_frame) = (0.0, 0.0);
    let mut pictures = Vec::new();
    let mut next_trace = 0.0;
    while t < 4.0 || t_plain < 4.0 {
        if t_plain <= t {
            let dt = plain.stable_dt();
            plain.step(dt)?;
            t_plain += dt;
        } else {
            let dt = flip.stable_dt();
            flip.step(dt)?;
            t += dt;
            if t >= next_frame && t <= 2.0 {
                pictures.push(picture(&flip, t));
                next_frame += 1.0 / 25.0;
            }
        }
        let now = t.min(t_plain);
        if now >= next_trace {
            trace.push((now, flip.filled_area() / area, plain.filled_area() / area));
            next_trace += 0.05;
        }
    }
    let last = trace[trace.len() - 1];
    println!(
        "  area filled at t = 4 s: {:.1} % with the density correction, {:.1} % without",
        100.0 * last.1,
        100.0 * last.2
    );
    write_table(
        cli.out.join("volume.csv"),
        &["t", "corrected", "uncorrected"],
        &trace
            .iter()
            .map(|&(t, a, b)| vec![number(t), number(a), number(b)])
            .collect::<Vec<_>>(),
    )?;
    Chart {
        title: "FLIP dam break: area the liquid fills / initial".into(),
        x_label: "t (s)".into(),
        y_label: "area / initial area".into(),
        series: vec![
            Series::line(
                "with the density correction",
                trace.iter().map(|p| (p.0, p.1)).collect(),
            ),
            Series::line("without", trace.iter().map(|p| (p.0, p.2)).collect()),
        ],
        ..Chart::default()
    }
    .write(cli.out.join("volume.png"), (900, 600))?;
    for (k, picture) in pictures.iter().enumerate().step_by(10) {
        particles(cli.out.join(format!("frame_{k}.png")), picture, (1000, 520))?;
    }
    particle_animation(cli.out.join("dam_break.gif"), &pictures, (640, 340), 40)?;
    println!("wrote {}/", cli.out.display());
    Ok(())
}

/// The particles coloured by speed band, over the box.
fn picture(flip: &Flip, t: f64) -> Particles {
    let h = flip.options().cell;
    let (w, top) = (
        (flip.options().nx - 1) as f64 * h,
        (flip.options().ny - 1) as f64 * h,
    );
    let mut groups = vec![
        ("< 1 m/s".to_owned(), Vec::new()),
        ("1–2 m/s".to_owned(), Vec::new()),
        ("> 2 m/s".to_owned(), Vec::new()),
    ];
    for (x, v) in flip.x.iter().zip(&flip.v) {
        let band = (v.norm() as usize).min(2);
        groups[band].1.push((x.x, x.y));
    }
    Particles {
        title: format!("FLIP 0.95 dam break, t = {t:.2} s"),
        groups,
        radius: 2,
        outline: vec![[(h, top), (h, h)], [(h, h), (w, h)], [(w, h), (w, top)]],
        bounds: ((0.0, w + h), (0.0, top + h)),
    }
}
