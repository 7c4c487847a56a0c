//! The 2-D Brusselator of SciMLBenchmarks' BRUSS problem (Hairer & Wanner, *Solving ODEs II*,
//! §IV.10), on an N × N periodic grid of the unit square:
//!
//!   u_t = 1 + u²v − 4.4u + α∇²u,   v_t = 3.4u − u²v + α∇²v,   α = 10,
//!
//! from u = 22·(y(1 − y))^{3/2}, v = 27·(x(1 − x))^{3/2} (x, y on N points from 0 to 1,
//! Δx = 1/(N − 1)), to t = 11.5. The benchmark's source term — 5 added to u_t inside the disc
//! (x − 0.3)² + (y − 0.6)² ≤ 0.1² from t = 1.1 — is on with `--forcing`: the `#[cell]` method
//! reads the cell's position and the time (`x`, `y`, `t` arguments; the grids carry the spacing).
//! It is off by default, as in the references `--reference` compares against.
//!
//! Stiff: diffusion's eigenvalues reach −8α/Δx² (−77 000 at N = 32), while the chemistry moves on
//! a time scale of 1. The run uses BDF at rtol = atol = 1e-6 five times — with the default
//! `LinearSolver::Auto`, with block-Jacobi, multigrid and Fourier BiCGSTAB
//! (`LinearSolver::Krylov`) and with the sparse LU (`LinearSolver::Direct`) — and prints the time, steps, Jacobians and
//! linear-solver work of each and how far apart the block-Jacobi and LU runs end.
//!
//! `cargo run --release --example brusselator [-- --n 64]` writes under `out/brusselator/`:
//! `u_<k>.png` (u at t = 0, 2.875, 5.75, 8.625, 11.5, colour bar 0 to 5) and `brusselator.csv`
//! (t, min, mean and max of u and v at those times).

use std::path::Path;
use std::time::Instant;

use clap::Parser;
use odyn::grid::{Boundary, Grid, GridState, Stencil};
use odyn::output::{number, write_table};
use odyn::plot::{Field, FieldStyle, field_image};
use odyn::{
    KrylovOptions, LinearSolver, Method, NewtonOptions, Preconditioner, Simulate, State,
    Trajectory, system,
};

/// The Brusselator: concentrations u and v on a periodic grid.
#[system(integrator = Bdf, rtol = 1e-6, atol = 1e-6)]
pub struct Brusselator {
    /// Concentration u.
    #[field]
    pub u: Grid,
    /// Concentration v.
    #[field]
    pub v: Grid,
    /// Diffusion coefficient α.
    pub alpha: f64,
    /// Cell size Δx.
    pub dx: f64,
    /// Whether the benchmark's source is on: 5 inside the disc (x − 0.3)² + (y − 0.6)² ≤ 0.1²
    /// from t = 1.1.
    pub forcing: bool,
}

#[system]
impl Brusselator {
    #[cell]
    fn reaction(&self, u: Stencil, v: Stencil, x: f64, y: f64, t: f64) -> [f64; 2] {
        let uuv = u.c * u.c * v.c;
        let diffusion = self.alpha / (self.dx * self.dx);
        let disc = (x - 0.3) * (x - 0.3) + (y - 0.6) * (y - 0.6) <= 0.01;
        let source = if self.forcing && disc && t >= 1.1 {
            5.0
        } else {
            0.0
        };
        [
            1.0 + uuv - 4.4 * u.c + diffusion * u.laplacian() + source,
            3.4 * u.c - uuv + diffusion * v.laplacian(),
        ]
    }
}

/// The BRUSS initial state on an n × n grid.
fn brusselator(n: usize, forcing: bool) -> odyn::Result<Brusselator> {
    let dx = 1.0 / (n - 1) as f64;
    let bump = |s: f64, scale: f64| scale * (s * (1.0 - s)).powf(1.5);
    Ok(Brusselator {
        u: Grid::from_fn(n, n, Boundary::Periodic, |_, j| bump(j as f64 * dx, 22.0))?
            .with_spacing(dx, dx)?,
        v: Grid::from_fn(n, n, Boundary::Periodic, |i, _| bump(i as f64 * dx, 27.0))?
            .with_spacing(dx, dx)?,
        alpha: 10.0,
        dx,
        forcing,
    })
}

#[derive(Parser)]
#[command(about = "The 2-D Brusselator (BRUSS) by BDF, sparse LU against Krylov solves")]
struct Cli {
    /// Cells along each side.
    #[arg(long, default_value_t = 32)]
    n: usize,
    /// Skip the sparse-LU run.
    #[arg(long)]
    krylov_only: bool,
    /// Switch on the benchmark's source (5 inside the disc of radius 0.1 about (0.3, 0.6) from
    /// t = 1.1); the references of `--reference` are of the problem without it.
    #[arg(long)]
    forcing: bool,
    /// A reference final state (2·N² numbers, u then v, cell i + N·j, one per line, as
    /// `scripts/bruss_reference.py` writes them): calibrate BDF and Rodas5P to a final error of
    /// 1e-6 (max |y − ref| / max |ref|) by a half-decade tolerance sweep, and time the loosest
    /// tolerance that meets it.
    #[arg(long)]
    reference: Option<std::path::PathBuf>,
    /// Instead of the comparison, run BDF at rtol = atol = `--tol` and write the final state to
    /// this file in the format of `--reference` (one value per line, 17 digits): how a reference
    /// made by another code is cross-checked (`--write-final ours.csv --tol 1e-11`).
    #[arg(long)]
    write_final: Option<std::path::PathBuf>,
    /// The tolerance of `--write-final`.
    #[arg(long, default_value_t = 1e-10, requires = "write_final")]
    tol: f64,
}

const T_END: f64 = 11.5;

fn main() -> odyn::Result<()> {
    let cli = Cli::parse();
    if cli.n < 3 {
        return Err(odyn::Error::InvalidInput {
            field: "--n".into(),
            reason: format!("needs at least 3 cells a side, got {}", cli.n),
        });
    }
    let dir = Path::new("out/brusselator");
    let model = brusselator(cli.n, cli.forcing)?;
    if let Some(path) = &cli.reference {
        return calibrate(&model, cli.n, path);
    }
    if let Some(path) = &cli.write_final {
        return write_final(&model, cli.tol, path);
    }
    let frames: Vec<f64> = (0..=4).map(|k| T_END * k as f64 / 4.0).collect();
    let unknowns = 2 * cli.n * cli.n;
    println!(
        "Brusselator, {0}×{0} periodic cells ({unknowns} unknowns), α = 10, BDF at rtol = atol = 1e-6 to t = {T_END}",
        cli.n
    );
    let run = |linear: LinearSolver| -> odyn::Result<(Trajectory<GridState>, f64)> {
        let start = Instant::now();
        let run = model
            .simulate()
            .integrator(Method::Bdf)
            .tolerances(1e-6, 1e-6)
            .newton(NewtonOptions {
                linear,
                ..NewtonOptions::default()
            })
            .duration(T_END)
            .save_at(&frames)
            .run()?;
        Ok((run, start.elapsed().as_secs_f64()))
    };
    let report = |name: &str, run: &Trajectory<GridState>, seconds: f64| {
        let s = &run.stats;
        println!(
            "  {name:<26} {seconds:8.3} s  {} steps, {} Jacobians, {} factorizations, {} linear solves",
            s.steps, s.jacobian_evaluations, s.factorizations, s.linear_solves
        );
    };
    let (auto, seconds) = run(LinearSolver::default())?;
    report("Auto (the default)", &auto, seconds);
    let (krylov, seconds) = run(LinearSolver::Krylov(KrylovOptions::default()))?;
    report("block-Jacobi BiCGSTAB", &krylov, seconds);
    let multigrid = LinearSolver::Krylov(KrylovOptions {
        preconditioner: Preconditioner::Multigrid,
        ..KrylovOptions::default()
    });
    let (multigrid, seconds) = run(multigrid)?;
    report("multigrid BiCGSTAB", &multigrid, seconds);
    let fourier = LinearSolver::Krylov(KrylovOptions {
        preconditioner: Preconditioner::Fourier,
        ..KrylovOptions::default()
    });
    let (fourier, seconds) = run(fourier)?;
    report("Fourier BiCGSTAB", &fourier, seconds);
    if !cli.krylov_only {
        let (direct, seconds) = run(LinearSolver::Direct)?;
        report("sparse LU", &direct, seconds);
        let (a, b) = (&krylov.last().state, &direct.last().state);
        let scale = b.as_slice().iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let apart = a
            .as_slice()
            .iter()
            .zip(b.as_slice())
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        println!(
            "  final states apart by {:.1e} of max |u, v|",
            apart / scale
        );
    }

    let mut rows = Vec::new();
    let style = FieldStyle {
        range: (0.0, 5.0),
        scale: (512 / cli.n).max(1) as u32,
        ..FieldStyle::default()
    };
    for (k, &t) in frames.iter().enumerate() {
        let state = &krylov.sample_at(t)?.state;
        let stats = |values: &[f64]| {
            let min = values.iter().copied().fold(f64::INFINITY, f64::min);
            let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let mean = values.iter().sum::<f64>() / values.len() as f64;
            [min, mean, max]
        };
        let (u, v) = (stats(state.field(0)), stats(state.field(1)));
        rows.push(
            std::iter::once(number(t))
                .chain(u.iter().chain(&v).map(|&x| number(x)))
                .collect::<Vec<_>>(),
        );
        let field = Field::new(cli.n, cli.n, state.field(0))
            .titled(if cli.forcing {
                "Brusselator, forced (colours span the frame's range)"
            } else {
                "Brusselator"
            })
            .named("u")
            .at_time(t);
        // Diffusion (α = 10) keeps the source's imprint to a few thousandths of u: a fixed
        // colour range would show a uniform square.
        let style = if cli.forcing && u[2] > u[0] {
            FieldStyle {
                range: (u[0], u[2]),
                ..style
            }
        } else {
            style
        };
        field_image(dir.join(format!("u_{k}.png")), field, style)?;
    }
    write_table(
        dir.join("brusselator.csv"),
        &["t", "u_min", "u_mean", "u_max", "v_min", "v_mean", "v_max"],
        &rows,
    )?;
    println!("wrote {}/u_0..4.png and brusselator.csv", dir.display());
    Ok(())
}

/// `--write-final`: BDF at rtol = atol = `tol` to t = 11.5, the final state written atomically.
fn write_final(model: &Brusselator, tol: f64, path: &Path) -> odyn::Result<()> {
    let start = Instant::now();
    let run = model
        .simulate()
        .integrator(Method::Bdf)
        .tolerances(tol, tol)
        .duration(T_END)
        .save_at(&[T_END])
        .run()?;
    let text: String = run
        .last()
        .state
        .as_slice()
        .iter()
        .map(|x| format!("{x:.17e}\n"))
        .collect();
    odyn::output::write_atomic(path, text.as_bytes())?;
    let s = &run.stats;
    println!(
        "BDF at {tol:e}: {:.1} s, {} steps, {} factorizations, {} solves; wrote {}",
        start.elapsed().as_secs_f64(),
        s.steps,
        s.factorizations,
        s.linear_solves,
        path.display()
    );
    Ok(())
}

/// The calibration of `--reference`: for BDF and Rodas5P (default linear solver), the loosest
/// rtol = atol in 1e-3, 3e-4, 1e-4, … whose final error is at most 1e-6 of max |ref|, with its
/// time (best of three runs) and work. Only the final state is kept (`save_at`), as a
/// benchmark would.
fn calibrate(model: &Brusselator, n: usize, path: &Path) -> odyn::Result<()> {
    let text = std::fs::read_to_string(path).map_err(|e| odyn::Error::InvalidInput {
        field: "--reference".into(),
        reason: format!("cannot read {}: {e}", path.display()),
    })?;
    let reference: Vec<f64> = text
        .split_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .map_err(|e| odyn::Error::InvalidInput {
            field: "--reference".into(),
            reason: format!("{}: {e}", path.display()),
        })?;
    if reference.len() != 2 * n * n {
        return Err(odyn::Error::InvalidInput {
            field: "--reference".into(),
            reason: format!("{} values for {} unknowns", reference.len(), 2 * n * n),
        });
    }
    let scale = reference.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    const TARGET: f64 = 1e-6;
    for method in [Method::Bdf, Method::Rodas5P] {
        for k in 0..16 {
            let tol = if k % 2 == 0 { 1e-3 } else { 3e-4 } * 10f64.powi(-(k / 2));
            let go = || {
                model
                    .simulate()
                    .integrator(method)
                    .tolerances(tol, tol)
                    .duration(T_END)
                    .save_at(&[T_END])
                    .run()
            };
            let run = go()?;
            let error = run
                .last()
                .state
                .as_slice()
                .iter()
                .zip(&reference)
                .fold(0.0f64, |m, (x, r)| m.max((x - r).abs()))
                / scale;
            if error <= TARGET {
                let mut best = f64::INFINITY;
                for _ in 0..3 {
                    let start = Instant::now();
                    go()?;
                    best = best.min(start.elapsed().as_secs_f64());
                }
                let s = &run.stats;
                println!(
                    "N = {n}, {}: tol {tol:.0e}, error {error:.2e}, {best:.3} s (best of 3), {} steps, {} Jacobians, {} factorizations, {} solves",
                    method.label(),
                    s.steps,
                    s.jacobian_evaluations,
                    s.factorizations,
                    s.linear_solves
                );
                break;
            }
        }
    }
    Ok(())
}
