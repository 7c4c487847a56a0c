//! Heat flow on the unit square, u_t = D∇²u with u = 0 on the edges, as a field model: the
//! right-hand side is written for one cell from its stencil, and odyn derives the sparse
//! Jacobian, predicts explicit Euler's stability limit from it, and solves the implicit steps
//! with sparse Cholesky.
//!
//! The initial temperature sin(πx)·sin(πy) + ½·sin(2πx)·sin(3πy) is separable: each term
//! decays as exp(−Dπ²(m² + k²)t), so the exact solution is known at every node and time. The
//! grid holds the n × n interior nodes of a vertex-centred mesh (dx = 1/(n + 1)), its edges held
//! at 0 by `Boundary::Dirichlet(0.0)`.
//!
//! The example prints explicit Euler's and RK4's limits as Gershgorin's discs of the assembled
//! Jacobian predict them (dx²/(4D) for explicit Euler) and as long runs measure them, then runs
//! explicit Euler just inside the limit, implicit Euler at 120× the limit, and Rodas5P
//! (adaptive), reporting each one's error against the exact solution, steps and time.
//!
//! `cargo run --release --example heat` writes under `out/heat/`: `heat.csv` (method, t, the
//! largest nodal error), `error.png` (those errors over time), and `start.png` /
//! `end.png` (the temperature at t = 0 and at the end of the implicit run).

use std::f64::consts::PI;
use std::path::Path;
use std::time::Instant;

use odyn::grid::{Boundary, Grid, GridState, Stencil};
use odyn::output::{number, write_table};
use odyn::plot::{Chart, Field, FieldStyle, Series, field_image};
use odyn::stability::{StabilityProbe, gershgorin_limit, measured_limit};
use odyn::{Method, Model, Simulate, Trajectory, system};

/// u_t = D∇²u on a grid of nodes dx apart.
#[system(integrator = ImplicitEuler)]
pub struct Heat {
    /// Temperature at the interior nodes.
    #[field]
    pub u: Grid,
    /// Diffusivity D.
    pub diffusivity: f64,
    /// Node spacing dx.
    pub dx: f64,
}

#[system]
impl Heat {
    #[cell]
    fn conduction(&self, u: Stencil) -> f64 {
        self.diffusivity * u.laplacian() / (self.dx * self.dx)
    }
}

/// The initial state's modes (m, k, amplitude).
const MODES: [(f64, f64, f64); 2] = [(1.0, 1.0, 1.0), (2.0, 3.0, 0.5)];
const D: f64 = 0.1;
const N: usize = 48;

/// The exact temperature at node (i, j) of a grid with spacing dx, at time t.
fn exact(dx: f64, i: usize, j: usize, t: f64) -> f64 {
    let (x, y) = ((i + 1) as f64 * dx, (j + 1) as f64 * dx);
    MODES
        .iter()
        .map(|&(m, k, a)| {
            a * (m * PI * x).sin() * (k * PI * y).sin() * (-D * PI * PI * (m * m + k * k) * t).exp()
        })
        .sum()
}

/// The largest nodal error of `state` at time t.
fn error(dx: f64, state: &GridState, t: f64) -> f64 {
    let n = state.nx();
    state
        .field(0)
        .iter()
        .enumerate()
        .map(|(k, u)| (u - exact(dx, k % n, k / n, t)).abs())
        .fold(0.0, f64::max)
}

/// Heat flow on the unit square, u_t = D∇²u with u = 0 on the edges, as a field model.
///
/// Writes its CSV files and charts under `out/heat/` (the example's source says what each
/// holds); takes no options.
#[derive(clap::Parser)]
struct Cli {}

fn main() -> odyn::Result<()> {
    <Cli as clap::Parser>::parse();
    let dir = Path::new("out/heat");
    let dx = 1.0 / (N as f64 + 1.0);
    let model = Heat {
        u: Grid::from_fn(N, N, Boundary::Dirichlet(0.0), |i, j| exact(dx, i, j, 0.0))?,
        diffusivity: D,
        dx,
    };
    let start = model.state();
    let limit = dx * dx / (4.0 * D);
    let predicted = gershgorin_limit(&model, 0.0, &start, Method::ExplicitEuler)?;
    let probe = StabilityProbe {
        steps: 20_000,
        precision: 1e-4,
        // One stable interval on a real negative spectrum: a coarse scan from below suffices.
        scan_ratio: 1.25,
        ..StabilityProbe::default()
    };
    let measured = measured_limit(&model, &start, Method::ExplicitEuler, limit, &probe)?;
    let grid_exact = limit / (N as f64 * PI / (2.0 * (N as f64 + 1.0))).sin().powi(2);
    println!(
        "Heat on {N}² interior nodes, D = {D}: explicit Euler limit dx²/(4D) = {limit:.4e}; \
         predicted {predicted:.4e}, measured {measured:.4e} (the grid's own 2/|λ_max| = \
         {grid_exact:.4e})"
    );
    let rk4 = gershgorin_limit(&model, 0.0, &start, Method::Rk4)?;
    let rk4_measured = measured_limit(&model, &start, Method::Rk4, rk4, &probe)?;
    println!(
        "  RK4: predicted {rk4:.4e} ({:.4}× explicit Euler's, RK4's reach on the negative real \
         axis over 2), measured {rk4_measured:.4e}",
        rk4 / predicted
    );
    let duration = 0.25;
    // Implicit Euler takes two steps of 120× the limit, so the run ends on t = duration.
    let big = duration / 2.0;
    let runs: [(String, Method, Option<f64>); 3] = [
        (
            "explicit Euler, 0.95× limit".into(),
            Method::ExplicitEuler,
            Some(0.95 * predicted),
        ),
        (
            format!("implicit Euler, {:.0}× limit", big / predicted),
            Method::ImplicitEuler,
            Some(big),
        ),
        ("Rodas5P, rtol 1e-6".into(), Method::Rodas5P, None),
    ];
    let mut series = Vec::new();
    let mut columns: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut last: Option<(f64, GridState)> = None;
    for (name, method, dt) in runs.iter().cloned() {
        let started = Instant::now();
        let simulation = model.simulate().integrator(method).duration(duration);
        let trajectory: Trajectory<GridState> = match dt {
            Some(dt) => simulation.dt(dt).save_at(&times(duration)).run()?,
            None => simulation
                .tolerances(1e-6, 1e-9)
                .save_at(&times(duration))
                .run()?,
        };
        let seconds = started.elapsed().as_secs_f64();
        let points: Vec<(f64, f64)> = (trajectory.samples.iter())
            .map(|s| (s.t, error(dx, &s.state, s.t)))
            .collect();
        let (end, worst) = (
            points.last().map_or(f64::NAN, |p| p.1),
            points.iter().map(|p| p.1).fold(0.0, f64::max),
        );
        println!(
            "  {name}: {} steps, {:.1} ms; largest nodal error {worst:.2e} over the run, \
             {end:.2e} at t = {duration}",
            trajectory.stats.steps,
            1e3 * seconds
        );
        if method == Method::ImplicitEuler {
            last = trajectory.samples.last().map(|s| (s.t, s.state.clone()));
        }
        series.push(Series::line(name.as_str(), points.clone()));
        columns.push(points);
    }
    let rows: Vec<Vec<String>> = (columns.iter().zip(&runs))
        .flat_map(|(points, (name, ..))| {
            points
                .iter()
                .map(move |&(t, e)| vec![name.clone(), number(t), number(e)])
        })
        .collect();
    write_table(dir.join("heat.csv"), &["method", "t", "max_error"], &rows)?;
    Chart {
        title: format!("Heat on {N}² nodes: largest nodal error against the exact solution"),
        x_label: "t".into(),
        y_label: "max |u − u_exact|".into(),
        log_y: true,
        series,
        ..Chart::default()
    }
    .write(dir.join("error.png"), (1000, 600))?;
    let style = FieldStyle {
        range: (-0.6, 1.1),
        scale: 8,
        ..FieldStyle::default()
    };
    let image = |values, t| {
        Field::new(N, N, values)
            .titled("Heat")
            .named("u")
            .at_time(t)
    };
    field_image(dir.join("start.png"), image(start.field(0), 0.0), style)?;
    if let Some((t, end)) = &last {
        field_image(dir.join("end.png"), image(end.field(0), *t), style)?;
    }
    // The semi-discrete solution decays each mode at the grid's rate
    // −(4D/dx²)(sin²(mπdx/2) + sin²(kπdx/2)): its distance from the exact one is the spatial
    // error no time integrator can go below.
    let floor = (0..N * N)
        .map(|c| {
            let (i, j) = (c % N, c / N);
            let (x, y) = ((i + 1) as f64 * dx, (j + 1) as f64 * dx);
            let grid: f64 = MODES
                .iter()
                .map(|&(m, k, a)| {
                    let s = |w: f64| (w * PI * dx / 2.0).sin().powi(2);
                    let rate = -4.0 * D / (dx * dx) * (s(m) + s(k));
                    a * (m * PI * x).sin() * (k * PI * y).sin() * (rate * duration).exp()
                })
                .sum();
            (grid - exact(dx, i, j, duration)).abs()
        })
        .fold(0.0, f64::max);
    println!("  the grid's own (spatial) error at t = {duration}: {floor:.2e}");
    println!("wrote out/heat/");
    Ok(())
}

/// 51 output times from 0 to `duration`.
fn times(duration: f64) -> Vec<f64> {
    (0..=50).map(|k| duration * k as f64 / 50.0).collect()
}
