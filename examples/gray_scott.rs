//! Gray–Scott reaction–diffusion in Pearson's setup ("Complex patterns in a simple system",
//! Science 261, 1993): u + 2v → 3v, v → P, fed at rate F and killed at rate k,
//!
//!   u_t = D_u∇²u − uv² + F(1 − u),   v_t = D_v∇²v + uv² − (F + k)v,
//!
//! D_u = 2e-5, D_v = 1e-5 on a periodic 2.5 × 2.5 square of 256² cells; u = 1, v = 0 except a
//! central 20 × 20-cell square at (u, v) = (1/2, 1/4), everything perturbed by ±1 % noise.
//!
//! odyn predicts explicit Euler's limit from Gershgorin's discs of the assembled Jacobian at
//! the unperturbed background (u, v) = (1, 0): 2/(8D_u/dx² + F), a few percent under the
//! diffusion-only dx²/(4D_u) because the feed F damps u too; both are printed, and one short run
//! on each side of the prediction checks it. Each named pattern then runs with explicit Euler at
//! Pearson's dt = 1; coral runs once more on a 128² grid, with explicit Euler at dt = 1 and
//! with implicit Euler at dt = 10 (past explicit Euler's limit there, 4.2), and the two are
//! compared.
//!
//! `cargo run --release --example gray_scott [-- --steps N]` writes under `out/gray_scott/`:
//! for each pattern, `<name>_<t>.png` (u, colour-mapped, every quarter of the run),
//! `<name>.gif` (u every 1/40 of the run; `--gif-frames` for fewer, `--pixels` for smaller) and `<name>.csv` (t, mean and range of u and v, the
//! share of cells where v > 0.1); `explicit_<t>.png`, `explicit.csv`, `implicit_<t>.png` and
//! `implicit.csv` for the comparison.

use std::path::Path;
use std::time::Instant;

use clap::Parser;
use odyn::grid::{Boundary, Grid, GridState};
use odyn::output::{number, write_table};
use odyn::plot::{Field, FieldStyle, field_animation, field_image};
use odyn::rand::{Rng, SeedableRng};
use odyn::stability::gershgorin_limit;
use odyn::{Method, Model, NewtonOptions, Simulate};

// The model, written once for the examples, tests and benches (`scenes/src/fields.rs`): two
// #[field] grids u, v and one #[cell] method: u′ = D_u∇²u − uv² + F(1 − u), v′ = D_v∇²v + uv² − (F
// + k)v.
use scenes::GrayScott;

/// The named (F, k) points (`GrayScott::PATTERNS`, with their sources).
const PATTERNS: [(&str, f64, f64); 3] = GrayScott::PATTERNS;

#[derive(Parser)]
#[command(about)]
struct Cli {
    /// Explicit Euler steps of dt = 1 per pattern.
    #[arg(long, default_value_t = 10_000)]
    steps: u64,
    /// Cells a side.
    #[arg(long, default_value_t = 256)]
    cells: usize,
    /// Cells a side of the explicit-against-implicit comparison (the implicit steps solve by
    /// block-Jacobi BiCGSTAB, `LinearSolver::Auto`; `cargo bench --bench gray_scott` times a
    /// step by size and solver).
    #[arg(long, default_value_t = 128)]
    implicit_cells: usize,
    /// Duration of the explicit-against-implicit comparison.
    #[arg(long, default_value_t = 1000)]
    implicit_time: u64,
    /// Frames of each pattern's GIF, at most 41 (0 writes no GIF).
    #[arg(long, default_value_t = 41)]
    gif_frames: usize,
    /// Side of each image's field in pixels, rounded down to whole pixels a cell.
    #[arg(long, default_value_t = 512)]
    pixels: u32,
}

/// How the images of a run are written.
#[derive(Clone, Copy)]
struct Look {
    /// Frames of the GIF (0 for none).
    gif_frames: usize,
    /// Side of the field in pixels.
    pixels: u32,
}

/// Pearson's initial state with ±1 % noise from a seeded generator; `noise = false` gives the
/// background (1, 0) alone.
fn pearson(n: usize, feed: f64, kill: f64, noise: bool) -> odyn::Result<GrayScott> {
    let mut rng = odyn::rand::rngs::StdRng::seed_from_u64(1993);
    let mut jitter = move || {
        if noise {
            1.0 + 0.01 * (2.0 * rng.random::<f64>() - 1.0)
        } else {
            1.0
        }
    };
    let square = |i: usize, j: usize| {
        let half = n / 2;
        let r = n * 10 / 256;
        (half - r..half + r).contains(&i) && (half - r..half + r).contains(&j)
    };
    let mut u = Vec::with_capacity(n * n);
    let mut v = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let (u0, v0) = if noise && square(i, j) {
                (0.5, 0.25)
            } else {
                (1.0, 0.0)
            };
            u.push(u0 * jitter());
            v.push(v0 * jitter());
        }
    }
    Ok(GrayScott {
        u: Grid::new(n, n, Boundary::Periodic, u)?,
        v: Grid::new(n, n, Boundary::Periodic, v)?,
        du: 2e-5,
        dv: 1e-5,
        feed,
        kill,
        dx: 2.5 / n as f64,
    })
}

/// One row of the summary CSV.
fn summary(t: f64, state: &GridState) -> Vec<String> {
    let stats = |values: &[f64]| {
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        let (lo, hi) = values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(*x), hi.max(*x))
            });
        (mean, lo, hi)
    };
    let (u, v) = (state.field(0), state.field(1));
    let ((um, ulo, uhi), (vm, vlo, vhi)) = (stats(u), stats(v));
    let active = v.iter().filter(|&&x| x > 0.1).count() as f64 / v.len() as f64;
    [t, um, ulo, uhi, vm, vlo, vhi, active].map(number).to_vec()
}

const HEADER: [&str; 8] = [
    "t", "u_mean", "u_min", "u_max", "v_mean", "v_min", "v_max", "v_active",
];

/// Runs `model` with `method` at `dt` for `steps` steps, writing PNG frames (every quarter), a
/// GIF (as `look` asks) and the summary CSV under `dir` as `<name>…`; returns the final state.
fn run(
    dir: &Path,
    name: &str,
    model: &GrayScott,
    method: Method,
    dt: f64,
    steps: u64,
    look: Look,
) -> odyn::Result<GridState> {
    let n = model.u.nx();
    let every = (steps / 40).max(1);
    let started = Instant::now();
    let trajectory = model
        .simulate()
        .integrator(method)
        .dt(dt)
        .steps(steps)
        .record_every(every)
        .run()?;
    let seconds = started.elapsed().as_secs_f64();
    println!(
        "  {name}: {steps} steps of {method:?} at dt = {dt}: {:.2} ms a step",
        1e3 * seconds / steps as f64
    );
    let style = FieldStyle {
        range: (0.2, 1.0),
        scale: (look.pixels / n as u32).max(1),
        ..FieldStyle::default()
    };
    let title = format!("Gray–Scott, {name}");
    let field = |state: &GridState| -> Vec<f64> { state.field(0).to_vec() };
    let frames: Vec<Vec<f64>> = trajectory.samples.iter().map(|s| field(&s.state)).collect();
    let quarter = (trajectory.samples.len() - 1) / 4;
    for (k, sample) in trajectory.samples.iter().enumerate() {
        if k > 0 && k % quarter.max(1) == 0 {
            let values = field(&sample.state);
            let image = Field::new(n, n, &values)
                .titled(&title)
                .named("u")
                .at_time(sample.t);
            field_image(
                dir.join(format!("{name}_{}.png", sample.t.round())),
                image,
                style,
            )?;
        }
    }
    if look.gif_frames > 0 {
        // Every k-th recorded sample, the first and about `gif_frames` in all.
        let stride = frames.len().div_ceil(look.gif_frames);
        let fields: Vec<Field<'_>> = frames
            .iter()
            .zip(&trajectory.samples)
            .step_by(stride)
            .map(|(values, sample)| {
                Field::new(n, n, values)
                    .titled(&title)
                    .named("u")
                    .at_time(sample.t)
            })
            .collect();
        field_animation(dir.join(format!("{name}.gif")), &fields, style, 10)?;
    }
    let rows: Vec<Vec<String>> = (trajectory.samples.iter())
        .map(|s| summary(s.t, &s.state))
        .collect();
    write_table(dir.join(format!("{name}.csv")), &HEADER, &rows)?;
    Ok(trajectory
        .samples
        .last()
        .expect("a run has samples")
        .state
        .clone())
}

fn main() -> odyn::Result<()> {
    let cli = Cli::parse();
    let dir = Path::new("out/gray_scott");
    let n = cli.cells;
    let (_, feed, kill) = PATTERNS[0];
    let background = pearson(n, feed, kill, false)?;
    let dx = background.dx;
    let diffusion_only = dx * dx / (4.0 * background.du);
    let predicted = gershgorin_limit(&background, 0.0, &background.state(), Method::ExplicitEuler)?;
    println!(
        "Gray–Scott on {n}² cells, dx = {dx:.3e}: explicit Euler limit predicted {predicted:.4} \
         (2/(8·D_u/dx² + F) = {:.4}; diffusion alone dx²/(4·D_u) = {diffusion_only:.4})",
        2.0 / (8.0 * background.du / (dx * dx) + feed)
    );
    // The background with noise excites every mode; the fastest decays below the limit and
    // grows above it by |1 + dt·λ| a step.
    let noisy = pearson(n, feed, kill, true)?;
    let mut start = noisy.state();
    start.field_mut(1).fill(0.0);
    start
        .field_mut(0)
        .iter_mut()
        .for_each(|u| *u = 1.0 + (*u - 1.0) * 1e-3);
    for factor in [0.99, 1.01] {
        let outcome = background
            .simulate()
            .initial_state(start.clone())
            .integrator(Method::ExplicitEuler)
            .dt(factor * predicted)
            .steps(4000)
            .record_every(4000)
            .divergence_limit(10.0)
            .run_partial()?;
        let verdict = match outcome.1 {
            Some(error) => format!("diverged ({error})"),
            None => "bounded".to_string(),
        };
        println!("  at {factor}× the prediction, 4000 steps: {verdict}");
    }
    for (name, feed, kill) in PATTERNS {
        let model = pearson(n, feed, kill, true)?;
        println!("{name}: F = {feed}, k = {kill}");
        run(
            dir,
            name,
            &model,
            Method::ExplicitEuler,
            1.0,
            cli.steps,
            Look {
                gif_frames: cli.gif_frames,
                pixels: cli.pixels,
            },
        )?;
    }
    // Coral grows steadily from the start, so the two runs have a moving pattern to disagree on.
    let (first, feed, kill) = PATTERNS[1];
    let model = pearson(cli.implicit_cells, feed, kill, true)?;
    let duration = cli.implicit_time;
    println!(
        "{first} on {0}² cells to t = {duration}: explicit Euler at dt = 1 against implicit \
         Euler at dt = 10 (one Newton iteration a step, the default linear solver: block-Jacobi \
         BiCGSTAB from 1 024 unknowns)",
        cli.implicit_cells
    );
    let explicit = run(
        dir,
        "explicit",
        &model,
        Method::ExplicitEuler,
        1.0,
        duration,
        Look {
            gif_frames: 0,
            pixels: cli.pixels,
        },
    )?;
    let implicit = {
        let started = Instant::now();
        let trajectory = model
            .simulate()
            .integrator(Method::ImplicitEuler)
            .newton(NewtonOptions::linearized())
            .dt(10.0)
            .steps(duration / 10)
            .record_every(duration / 40)
            .run()?;
        println!(
            "  implicit: {} steps of ImplicitEuler at dt = 10: {:.0} ms a step",
            duration / 10,
            1e3 * started.elapsed().as_secs_f64() / (duration / 10) as f64
        );
        let rows: Vec<Vec<String>> = (trajectory.samples.iter())
            .map(|s| summary(s.t, &s.state))
            .collect();
        write_table(dir.join("implicit.csv"), &HEADER, &rows)?;
        let last = trajectory.samples.last().expect("a run has samples");
        let values = last.state.field(0);
        let image = Field::new(cli.implicit_cells, cli.implicit_cells, values)
            .titled("Gray–Scott, implicit Euler")
            .named("u")
            .at_time(last.t);
        let style = FieldStyle {
            range: (0.2, 1.0),
            scale: 4,
            ..FieldStyle::default()
        };
        field_image(dir.join(format!("implicit_{duration}.png")), image, style)?;
        last.state.clone()
    };
    let difference = explicit
        .field(0)
        .iter()
        .zip(implicit.field(0))
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let mean = |s: &GridState| s.field(1).iter().sum::<f64>() / s.field(1).len() as f64;
    println!(
        "  at t = {duration}: max |u_explicit − u_implicit| = {difference:.3}; mean v {:.4} \
         (explicit) and {:.4} (implicit)",
        mean(&explicit),
        mean(&implicit)
    );
    println!("wrote out/gray_scott/");
    Ok(())
}
