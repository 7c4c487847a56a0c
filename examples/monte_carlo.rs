//! Monte Carlo with odyn's ensembles: π by hit-or-miss, and a pendulum whose initial angle is
//! uncertain.
//!
//! - **π**: N points uniform in the unit square; the fraction inside the quarter disc times 4
//!   estimates π. Each point hits with probability p = π/4, so the estimate's standard deviation
//!   is exactly 4·√(p(1 − p)/N) = √(π(4 − π)/N). 400 members each estimate π at N = 10 … 10⁶;
//!   the RMS error over the members is plotted against N with that line, and the fitted log-log
//!   slope must be −½.
//! - **Pendulum**: θ″ = −(g/L)·sin θ with g = 9.81, L = 1, θ₀ ~ Normal(1.0, 0.1²) rad, ω₀ = 0,
//!   integrated by Yoshida 4 at dt = 0.01 to t = 20 s. Because the period grows with the
//!   amplitude, the members dephase: the mean of θ(t) decays while each member keeps its
//!   amplitude. The mean and the 5–95 % quantile band over 1000 members are plotted.
//!
//! `cargo run --release --example monte_carlo` writes under `out/monte_carlo/`: `pi.csv`,
//! `pi.png`, `pendulum.csv` (t, mean, standard deviation, 5 %, 50 %, 95 % quantiles) and
//! `pendulum.png`.
//!
//! # Sharded: on a cluster, or under any driver
//!
//! `--shard k/n` runs shard k of n of the pendulum members (0 ≤ k < n ≤ members) and writes
//! their raw results to `OUT/pendulum-shard-k-of-n.csv`, whole or not at all; `--merge FILES…`
//! merges the files of every shard into the `pendulum.csv` and `pendulum.png` that the
//! one-process run writes, byte for byte, and refuses (exit status 1, the shards named on
//! standard error) when a shard is missing, given twice, cut short or written twice. The flags
//! name no scheduler: a Slurm job array, GNU parallel or a Python loop hands out k and n. The
//! contract and the Slurm recipe that `scripts/slurm.sh` runs on a real Slurm are in
//! `docs/book/src/distributed.md`.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use odyn::ensemble::{Ensemble, MemberRng, Members, Shard};
use odyn::output::{number, write_table};
use odyn::plot::{Chart, Series};
use odyn::prelude::*;
use odyn::rand::Rng;

/// A simple pendulum.
#[system]
#[derive(Clone, Copy)]
pub struct Pendulum {
    /// Angle from the vertical (rad).
    #[position]
    pub theta: f64,
    /// Angular velocity (rad/s).
    #[velocity]
    pub omega: f64,
    /// Gravity (m/s²).
    pub g: f64,
    /// Length (m).
    pub length: f64,
}

#[system]
impl Pendulum {
    fn acceleration(&self) -> f64 {
        -self.g / self.length * self.theta.sin()
    }
}

/// π by hit-or-miss and an uncertain pendulum, as ensembles.
#[derive(Parser)]
#[command(about)]
struct Cli {
    /// Pendulum ensemble members.
    #[arg(long, default_value_t = 1000)]
    members: u64,
    /// Base seed of every member's generator.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Run only shard k of n of the pendulum members (`3/10`) and write their raw results to
    /// OUT/pendulum-shard-k-of-n.csv.
    #[arg(long, value_parser = parse_shard)]
    shard: Option<Shard>,
    /// Merge the files of every shard into the pendulum statistics instead of running.
    #[arg(long, num_args = 1.., conflicts_with = "shard")]
    merge: Vec<PathBuf>,
    /// Output directory.
    #[arg(long, default_value = "out/monte_carlo")]
    out: PathBuf,
}

fn parse_shard(text: &str) -> Result<Shard, String> {
    Shard::parse(text).map_err(|e| e.to_string())
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
    let ensemble = Ensemble {
        members: cli.members,
        seed: cli.seed,
        shard: cli.shard.unwrap_or(Shard::WHOLE),
        progress: true,
    };
    if let Some(shard) = cli.shard {
        let members = ensemble.run(pendulum_member)?;
        let path = cli.out.join(format!(
            "pendulum-shard-{}-of-{}.csv",
            shard.index, shard.count
        ));
        members.write_csv(&path)?;
        println!("wrote {} members to {}", members.rows.len(), path.display());
        return Ok(());
    }
    let members = if cli.merge.is_empty() {
        pi(&cli.out, cli.seed)?;
        ensemble.run(pendulum_member)?
    } else {
        let clock = Instant::now();
        let members = Members::merge_files(&cli.merge)?;
        println!(
            "merged {} shard files, {} members, in {:.2} s",
            cli.merge.len(),
            members.rows.len(),
            clock.elapsed().as_secs_f64()
        );
        members
    };
    let clock = Instant::now();
    pendulum_report(&cli.out, &members)?;
    println!(
        "wrote {}/ (statistics and plot in {:.2} s)",
        cli.out.display(),
        clock.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Sample sizes N = 10, 10^1.5, …, 10⁶.
fn sample_sizes() -> Vec<u64> {
    (2..=12)
        .map(|k| 10f64.powf(f64::from(k) / 2.0).round() as u64)
        .collect()
}

/// 4·(hits/N) with N points uniform in the unit square.
fn pi_estimate(n: u64, rng: &mut MemberRng) -> f64 {
    let mut hits = 0u64;
    for _ in 0..n {
        let (x, y): (f64, f64) = (rng.random(), rng.random());
        hits += u64::from(x * x + y * y <= 1.0);
    }
    4.0 * hits as f64 / n as f64
}

/// The π study: RMS error over 400 members against N, with the exact √(π(4 − π)/N).
fn pi(dir: &Path, seed: u64) -> odyn::Result<()> {
    let sizes = sample_sizes();
    let ensemble = Ensemble {
        members: 400,
        seed,
        ..Ensemble::default()
    };
    let members =
        ensemble.run(|_, rng| Ok(sizes.iter().map(|&n| pi_estimate(n, rng)).collect()))?;
    let count = members.rows.len() as f64;
    let rms: Vec<f64> = (0..sizes.len())
        .map(|k| {
            let sum: f64 = members.rows.iter().map(|(_, v)| (v[k] - PI).powi(2)).sum();
            (sum / count).sqrt()
        })
        .collect();
    let theory = |n: u64| (PI * (4.0 - PI) / n as f64).sqrt();
    let points: Vec<(f64, f64)> = sizes
        .iter()
        .map(|&n| (n as f64).ln())
        .zip(rms.iter().map(|r| r.ln()))
        .collect();
    let slope = least_squares_slope(&points);
    println!("π by hit-or-miss, 400 members: RMS error against N (theory √(π(4 − π)/N))");
    println!("  {:>9} {:>11} {:>11} {:>7}", "N", "RMS", "theory", "ratio");
    let mut rows = Vec::new();
    for (&n, &r) in sizes.iter().zip(&rms) {
        println!(
            "  {n:>9} {r:>11.3e} {:>11.3e} {:>7.3}",
            theory(n),
            r / theory(n)
        );
        rows.push(vec![n.to_string(), number(r), number(theory(n))]);
    }
    println!("  fitted slope {slope:.3} (theory −0.5)");
    write_table(dir.join("pi.csv"), &["n", "rms_error", "theory"], &rows)?;
    Chart {
        title: format!("π by hit-or-miss: RMS error over 400 members (fitted slope {slope:.3})"),
        x_label: "points N".into(),
        y_label: "RMS error of the estimate".into(),
        log_x: true,
        log_y: true,
        series: vec![
            Series::markers(
                "measured",
                sizes
                    .iter()
                    .map(|&n| n as f64)
                    .zip(rms.iter().copied())
                    .collect(),
            ),
            Series::line(
                "√(π(4 − π)/N)",
                sizes.iter().map(|&n| (n as f64, theory(n))).collect(),
            ),
        ],
        ..Chart::default()
    }
    .write(dir.join("pi.png"), (900, 600))
}

fn least_squares_slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let num: f64 = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let den: f64 = points.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    num / den
}

/// Recorded every 10 steps of dt = 0.01 to t = 20: 201 times.
const DT: f64 = 0.01;
const STEPS: u64 = 2000;
const EVERY: u64 = 10;

/// One pendulum: θ₀ ~ Normal(1.0, 0.1²) by Box–Muller, θ(t) at the recorded times.
fn pendulum_member(_: u64, rng: &mut MemberRng) -> odyn::Result<Vec<f64>> {
    let (u1, u2): (f64, f64) = (rng.random(), rng.random());
    let normal = (-2.0 * (1.0 - u1).ln()).sqrt() * (2.0 * PI * u2).cos();
    let pendulum = Pendulum {
        theta: 1.0 + 0.1 * normal,
        omega: 0.0,
        g: 9.81,
        length: 1.0,
    };
    let run = pendulum
        .simulate()
        .integrator(Method::Yoshida4)
        .dt(DT)
        .steps(STEPS)
        .record_every(EVERY)
        .run()?;
    Ok(run.samples.iter().map(|s| s.state.theta).collect())
}

fn pendulum_report(dir: &Path, members: &Members) -> odyn::Result<()> {
    let stats = members.statistics()?;
    let times: Vec<f64> = (0..stats.mean.len())
        .map(|k| k as f64 * EVERY as f64 * DT)
        .collect();
    let mut rows = Vec::new();
    let (mut low, mut median, mut high) = (Vec::new(), Vec::new(), Vec::new());
    for (k, &t) in times.iter().enumerate() {
        let q = |p| stats.quantile(k, p);
        let (q05, q50, q95) = (q(0.05)?, q(0.5)?, q(0.95)?);
        low.push((t, q05));
        median.push((t, q50));
        high.push((t, q95));
        rows.push(vec![
            number(t),
            number(stats.mean[k]),
            number(stats.variance[k].sqrt()),
            number(q05),
            number(q50),
            number(q95),
        ]);
    }
    let last = times.len() - 1;
    println!(
        "\nPendulum, θ₀ ~ N(1.0, 0.1²), {} members, Yoshida 4 at dt = {DT}: mean θ {:.4} at t = 0, \
         {:.4} at t = {}; 5–95 % band {:.4} … {:.4} at t = {}",
        members.rows.len(),
        stats.mean[0],
        stats.mean[last],
        times[last],
        low[last].1,
        high[last].1,
        times[last]
    );
    write_table(
        dir.join("pendulum.csv"),
        &["t", "mean", "std", "q05", "q50", "q95"],
        &rows,
    )?;
    Chart {
        title: format!(
            "Pendulum with uncertain θ₀ ~ N(1.0, 0.1²): {} members",
            members.rows.len()
        ),
        x_label: "t [s]".into(),
        y_label: "θ [rad]".into(),
        series: vec![
            Series::line(
                "mean",
                times
                    .iter()
                    .copied()
                    .zip(stats.mean.iter().copied())
                    .collect(),
            ),
            Series::line("median", median),
            Series::line("5 % quantile", low),
            Series::line("95 % quantile", high),
        ],
        ..Chart::default()
    }
    .write(dir.join("pendulum.png"), (1000, 600))
}
