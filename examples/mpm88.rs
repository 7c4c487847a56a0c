//! The 88-line MLS-MPM program's scene in odyn (`mpm88.py`, shipped with Taichi; Hu et al.,
//! SIGGRAPH 2018), timed per substep: the odyn side of `scripts/taichi_mpm88.py`.
//!
//! 8 192 particles of a weakly compressible fluid drop at 1 m/s from [0.2, 0.6]² in a unit box
//! of 128² nodes, dt = 2·10⁻⁴ s (`scenes::hybrid::mpm88`; more particles get a finer grid and a
//! shorter step, the same particles per cell and Courant number).
//!
//! `cargo run --release --example mpm88 [-- --particles 32768 --threads 2]` prints the cost per
//! substep (best of `--repeats` runs of `--substeps`); `--input positions.csv --grid N --dt DT`
//! starts from given positions (the race script's, so Taichi and odyn start alike), and
//! `--check K --output out.csv` writes the positions after K substeps.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use odyn::hybrid::mpm::Mpm;
use odyn::nalgebra::Vector2;
use odyn::output::{number, write_table};
// The 88-line program's scene (`scenes/src/hybrid.rs`).
use scenes::hybrid::{mpm88, mpm88_from};

/// The 88-line MLS-MPM scene, timed.
#[derive(Parser)]
#[command(about)]
struct Cli {
    /// Particles (drawn uniformly from [0.2, 0.6]²), unless --input gives them.
    #[arg(long, default_value_t = 8192)]
    particles: usize,
    /// Start positions, a CSV of x,y with a header line.
    #[arg(long)]
    input: Option<PathBuf>,
    /// Nodes a side with --input.
    #[arg(long, default_value_t = 128)]
    grid: usize,
    /// The step with --input (s).
    #[arg(long, default_value_t = 2e-4)]
    dt: f64,
    /// Rayon threads.
    #[arg(long, default_value_t = 1)]
    threads: usize,
    /// Substeps timed per run.
    #[arg(long, default_value_t = 2000)]
    substeps: usize,
    /// Runs; the fastest is reported.
    #[arg(long, default_value_t = 3)]
    repeats: usize,
    /// Substeps before the positions written to --output.
    #[arg(long, default_value_t = 20)]
    check: usize,
    /// Where to write the positions after --check substeps.
    #[arg(long)]
    output: Option<PathBuf>,
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

fn run(cli: Cli) -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
    let start = read(&cli)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(cli.threads)
        .build()?;
    pool.install(|| -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
        if let Some(path) = &cli.output {
            let (mut mpm, dt) = start()?;
            for _ in 0..cli.check {
                mpm.step(dt)?;
            }
            let rows: Vec<Vec<String>> = mpm
                .x
                .iter()
                .map(|x| vec![number(x.x), number(x.y)])
                .collect();
            write_table(path, &["x", "y"], &rows)?;
        }
        let mut best = f64::INFINITY;
        let mut particles = 0;
        for _ in 0..cli.repeats.max(1) {
            let (mut mpm, dt) = start()?;
            particles = mpm.x.len();
            mpm.step(dt)?;
            let clock = Instant::now();
            for _ in 0..cli.substeps {
                mpm.step(dt)?;
            }
            best = best.min(clock.elapsed().as_secs_f64() / cli.substeps.max(1) as f64);
        }
        println!(
            "{particles} particles, {} threads: {:.4} ms per substep",
            cli.threads,
            1e3 * best
        );
        Ok(())
    })
}

/// What starts a run: the scene from --input, or drawn.
type Start = Box<dyn Fn() -> odyn::Result<(Mpm, f64)> + Send + Sync>;

fn read(cli: &Cli) -> Result<Start, Box<dyn std::error::Error + Send + Sync>> {
    let Some(path) = &cli.input else {
        let particles = cli.particles;
        return Ok(Box::new(move || mpm88(particles)));
    };
    let mut positions = Vec::new();
    for line in std::fs::read_to_string(path)?.lines().skip(1) {
        let (x, y) = line.split_once(',').ok_or("a line without x,y")?;
        positions.push(Vector2::new(x.trim().parse()?, y.trim().parse()?));
    }
    let (grid, dt) = (cli.grid, cli.dt);
    Ok(Box::new(move || Ok((mpm88_from(&positions, grid)?, dt))))
}
