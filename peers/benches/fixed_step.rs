//! odyn against the same method written by hand and against two peer crates, `ode_solvers` and
//! `differential-equations`, on the same problems from the same initial states.
//!
//! `cargo bench --manifest-path peers/Cargo.toml --bench fixed_step`. Every variant of a group
//! runs side by side in one process; compare medians within a group (the machine is shared, so
//! absolute times drift between runs).
//!
//! - `lorenz_rk4`: 10⁶ classical RK4 steps of dt = 1e-5 (to t = 10) on Lorenz, σ = 10, ρ = 28,
//!   β = 8/3, from (1, 1, 1).
//! - `spring_rk4`: the same on the damped spring m·ẍ = −k·x − b·ẋ, k = 50, b = 0.5, m = 1, from
//!   (x, v) = (1, 0), in first-order form y = (x, v).
//! - `stiff`: implicit (backward) Euler, 10⁴ steps of dt = 1e-3 (to t = 10) on van der Pol with
//!   μ = 1000, y₁′ = y₂, y₂′ = μ(1 − y₁²)y₂ − y₁, from (2, 0). `ode_solvers` has no implicit
//!   method (only `Rk4`, `Dopri5` and `Dop853`), so it sits this group out.
//!
//! The variants, each returning its final state and nothing else:
//!
//! - `odyn`: the `#[system]` model stepped through [`Integrator::step`], as a game loop does.
//! - `hand_written`: the method written out on plain `[f64; N]` arrays — the floor.
//! - `ode_solvers`: `ode_solvers::Rk4::new(..).integrate()`, its fixed-step RK4.
//! - `differential_equations`: `ExplicitRungeKutta::rk4(dt)` (fixed-step classical RK4) and
//!   `ImplicitRungeKutta::backward_euler(dt)` (fixed-step implicit Euler), stepped through their
//!   `OrdinaryNumericalMethod::step`, the step-level API matching odyn's.
//!
//! The peers' own costs are kept, not worked around:
//!
//! - `ode_solvers::Rk4::integrate` has no output-free mode: it pushes (t, y) for every step into
//!   vectors preallocated for `steps` entries — `steps + 1` with the initial point, so they also
//!   grow once at the very end. For Lorenz that is 32 MB written per run.
//! - `differential-equations`' fixed-step methods run a generic tableau loop and save the previous
//!   step for interpolation. Its `backward_euler` is simplified Newton (the Jacobian is refreshed
//!   on the first iteration and then every four), stops on an absolute 1e-10 residual or update,
//!   builds a fresh heap Newton matrix at each refresh and clones its right-hand side every
//!   iteration. It gets the analytic Jacobian (its default is finite differences).
//!
//! Before anything is timed, `main` runs every variant once, prints the final states and asserts
//! that they agree (see [`check_agreement`]).

use std::hint::black_box;

use differential_equations::linalg::Matrix;
use differential_equations::methods::{ExplicitRungeKutta, ImplicitRungeKutta};
use differential_equations::ode::{ODE, OrdinaryNumericalMethod};
use odyn::integrators::{ImplicitEuler, Integrator, Rk4};
use odyn::prelude::*;
use odyn::{NewtonOptions, Stats};

/// RK4 groups: 10⁶ steps of 1e-5, to t = 10.
const RK4_DT: f64 = 1e-5;
const RK4_STEPS: u64 = 1_000_000;

/// Stiff group: 10⁴ steps of 1e-3, to t = 10.
const STIFF_DT: f64 = 1e-3;
const STIFF_STEPS: u64 = 10_000;

use scenes::*;

fn main() {
    check_agreement();
    divan::main();
}

// ---------------------------------------------------------------------------------------------
// Models (`scenes/src/`). Each also gets its right-hand side on plain arrays, with the arithmetic
// of its `#[system]` function, for the hand-written loops, and implements the peers' traits
// through it, on the wrapper `Peer` (the models and the traits are both other crates').

/// A model's initial state and right-hand side on plain arrays.
trait Arrays<const N: usize> {
    /// The initial state.
    fn y0(&self) -> [f64; N];
    /// f(y), with the arithmetic of the model's `#[system]` function.
    fn f(&self, y: [f64; N]) -> [f64; N];
}

/// A model seen by the peer crates.
#[derive(Clone, Copy)]
struct Peer<M>(M);

const LORENZ: Lorenz = Lorenz {
    x: 1.0,
    y: 1.0,
    z: 1.0,
    sigma: 10.0,
    rho: 28.0,
    beta: 8.0 / 3.0,
};

impl Arrays<3> for Lorenz {
    fn y0(&self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }

    fn f(&self, [x, y, z]: [f64; 3]) -> [f64; 3] {
        [
            self.sigma * (y - x),
            x * (self.rho - z) - y,
            x * y - self.beta * z,
        ]
    }
}

impl ode_solvers::System<f64, ode_solvers::Vector3<f64>> for Peer<Lorenz> {
    fn system(&self, _: f64, y: &ode_solvers::Vector3<f64>, dy: &mut ode_solvers::Vector3<f64>) {
        *dy = self.0.f((*y).into()).into();
    }
}

impl ODE<f64, [f64; 3]> for Peer<Lorenz> {
    fn diff(&self, _: f64, y: &[f64; 3], dydt: &mut [f64; 3]) {
        *dydt = self.0.f(*y);
    }
}

const SPRING: Spring = Spring {
    x: 1.0,
    v: 0.0,
    k: 50.0,
    b: 0.5,
    m: 1.0,
};

impl Arrays<2> for Spring {
    fn y0(&self) -> [f64; 2] {
        [self.x, self.v]
    }

    fn f(&self, [x, v]: [f64; 2]) -> [f64; 2] {
        [v, (-self.k * x - self.b * v) / self.m]
    }
}

impl ode_solvers::System<f64, ode_solvers::Vector2<f64>> for Peer<Spring> {
    fn system(&self, _: f64, y: &ode_solvers::Vector2<f64>, dy: &mut ode_solvers::Vector2<f64>) {
        *dy = self.0.f((*y).into()).into();
    }
}

impl ODE<f64, [f64; 2]> for Peer<Spring> {
    fn diff(&self, _: f64, y: &[f64; 2], dydt: &mut [f64; 2]) {
        *dydt = self.0.f(*y);
    }
}

const VAN_DER_POL: VanDerPol = VanDerPol {
    y1: 2.0,
    y2: 0.0,
    mu: 1000.0,
};

impl Arrays<2> for VanDerPol {
    fn y0(&self) -> [f64; 2] {
        [self.y1, self.y2]
    }

    fn f(&self, [y1, y2]: [f64; 2]) -> [f64; 2] {
        [y2, self.mu * (1.0 - y1 * y1) * y2 - y1]
    }
}

/// van der Pol's ∂f/∂y, row by row.
fn van_der_pol_df(model: &VanDerPol, [y1, y2]: [f64; 2]) -> [[f64; 2]; 2] {
    [
        [0.0, 1.0],
        [-2.0 * model.mu * y1 * y2 - 1.0, model.mu * (1.0 - y1 * y1)],
    ]
}

impl ODE<f64, [f64; 2]> for Peer<VanDerPol> {
    fn diff(&self, _: f64, y: &[f64; 2], dydt: &mut [f64; 2]) {
        *dydt = self.0.f(*y);
    }

    fn jacobian(&self, _: f64, y: &[f64; 2], j: &mut Matrix<f64>) {
        for (r, row) in van_der_pol_df(&self.0, *y).into_iter().enumerate() {
            for (c, entry) in row.into_iter().enumerate() {
                j[(r, c)] = entry;
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Drivers.

/// Steps a model with odyn's integrator `I` through the [`Integrator`] trait.
fn odyn_run<M: Model, I: Integrator<M>>(model: &M, dt: f64, steps: u64) -> M::State {
    let mut state = model.state();
    let mut scratch = state.clone();
    let mut stats = Stats::default();
    let mut integrator = I::start(model, 0.0, &state, &NewtonOptions::default(), &mut stats)
        .expect("a fixed-size model always starts");
    for n in 0..steps {
        integrator
            .step(
                model,
                n as f64 * dt,
                dt,
                &mut state,
                &mut scratch,
                &mut stats,
            )
            .expect("step");
    }
    state
}

/// Classical RK4 written out on plain arrays.
fn hand_rk4<const N: usize>(
    f: impl Fn([f64; N]) -> [f64; N],
    mut y: [f64; N],
    dt: f64,
    steps: u64,
) -> [f64; N] {
    let probe = |y: &[f64; N], a: f64, k: &[f64; N]| std::array::from_fn(|i| y[i] + a * k[i]);
    for _ in 0..steps {
        let k1 = f(y);
        let k2 = f(probe(&y, 0.5 * dt, &k1));
        let k3 = f(probe(&y, 0.5 * dt, &k2));
        let k4 = f(probe(&y, dt, &k3));
        for (i, yi) in y.iter_mut().enumerate() {
            *yi += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    y
}

/// Implicit Euler on van der Pol written out: Newton from yₙ with the analytic 2×2 Jacobian,
/// each linear solve by Cramer's rule, until |Δᵢ| ≤ 1e-10·(1 + |yᵢ|) for both components (odyn's
/// default rule), at most 20 iterations.
fn hand_implicit_euler(model: &VanDerPol, mut y: [f64; 2], h: f64, steps: u64) -> [f64; 2] {
    const TOL: f64 = 1e-10;
    const MAX_ITERS: u32 = 20;
    for _ in 0..steps {
        let start = y;
        let mut converged = false;
        for _ in 0..MAX_ITERS {
            // (I − h·J)·Δ = yₙ + h·f(y) − y
            let f = model.f(y);
            let [[j11, j12], [j21, j22]] = van_der_pol_df(model, y);
            let [a, b, c, d] = [1.0 - h * j11, -h * j12, -h * j21, 1.0 - h * j22];
            let [r1, r2] = [start[0] + h * f[0] - y[0], start[1] + h * f[1] - y[1]];
            let det = a * d - b * c;
            let delta = [(r1 * d - b * r2) / det, (a * r2 - c * r1) / det];
            y[0] += delta[0];
            y[1] += delta[1];
            converged = delta
                .iter()
                .zip(&y)
                .all(|(di, yi)| di.abs() <= TOL * (1.0 + yi.abs()));
            if converged {
                break;
            }
        }
        assert!(converged, "hand-written Newton did not converge");
    }
    y
}

/// `ode_solvers`' fixed-step RK4 from t = 0 to `steps·dt`; it records every step (see the
/// crate docs), of which only the last is returned.
fn ode_solvers_rk4<const N: usize>(
    system: impl ode_solvers::System<f64, ode_solvers::SVector<f64, N>>,
    y0: [f64; N],
    dt: f64,
    steps: u64,
) -> [f64; N] {
    let mut rk4 = ode_solvers::Rk4::new(system, 0.0, y0.into(), steps as f64 * dt, dt);
    rk4.integrate().expect("ode_solvers::Rk4::integrate");
    let ys = rk4.y_out();
    assert_eq!(
        ys.len() as u64,
        steps + 1,
        "ode_solvers took a different number of steps"
    );
    ys[ys.len() - 1].into()
}

/// Steps a `differential-equations` method exactly `steps` times through its
/// [`OrdinaryNumericalMethod`] trait, keeping only the current state. (`IVP::solve` would add its
/// output handler, and since it accumulates t += dt — 9.9999999998 after 10⁶ steps of 1e-5 — and
/// then steps to t = 10 exactly, one extra sliver of a step.)
fn differential_equations_run<Y, S>(
    mut method: S,
    ode: &impl ODE<f64, Y>,
    y0: Y,
    tf: f64,
    steps: u64,
) -> Y
where
    Y: differential_equations::traits::State<f64>,
    S: OrdinaryNumericalMethod<f64, Y>,
{
    method.init(ode, 0.0, tf, &y0).expect("init");
    for _ in 0..steps {
        method.step(ode).expect("step");
    }
    method.y().clone()
}

// ---------------------------------------------------------------------------------------------
// Benches.

mod lorenz_rk4 {
    use super::*;

    #[divan::bench(sample_count = 20)]
    pub fn odyn() -> LorenzState {
        odyn_run::<_, Rk4<_>>(&black_box(LORENZ), RK4_DT, RK4_STEPS)
    }

    #[divan::bench(sample_count = 20)]
    pub fn hand_written() -> [f64; 3] {
        let model = black_box(LORENZ);
        hand_rk4(|y| model.f(y), model.y0(), RK4_DT, RK4_STEPS)
    }

    #[divan::bench(sample_count = 20)]
    pub fn ode_solvers() -> [f64; 3] {
        let model = black_box(LORENZ);
        ode_solvers_rk4(Peer(model), model.y0(), RK4_DT, RK4_STEPS)
    }

    #[divan::bench(sample_count = 20)]
    pub fn differential_equations() -> [f64; 3] {
        let model = black_box(LORENZ);
        let rk4 = ExplicitRungeKutta::rk4(RK4_DT).max_steps(RK4_STEPS as usize);
        let tf = RK4_STEPS as f64 * RK4_DT;
        differential_equations_run(rk4, &Peer(model), model.y0(), tf, RK4_STEPS)
    }
}

mod spring_rk4 {
    use super::*;

    #[divan::bench(sample_count = 20)]
    pub fn odyn() -> SpringState {
        odyn_run::<_, Rk4<_>>(&black_box(SPRING), RK4_DT, RK4_STEPS)
    }

    #[divan::bench(sample_count = 20)]
    pub fn hand_written() -> [f64; 2] {
        let model = black_box(SPRING);
        hand_rk4(|y| model.f(y), model.y0(), RK4_DT, RK4_STEPS)
    }

    #[divan::bench(sample_count = 20)]
    pub fn ode_solvers() -> [f64; 2] {
        let model = black_box(SPRING);
        ode_solvers_rk4(Peer(model), model.y0(), RK4_DT, RK4_STEPS)
    }

    #[divan::bench(sample_count = 20)]
    pub fn differential_equations() -> [f64; 2] {
        let model = black_box(SPRING);
        let rk4 = ExplicitRungeKutta::rk4(RK4_DT).max_steps(RK4_STEPS as usize);
        let tf = RK4_STEPS as f64 * RK4_DT;
        differential_equations_run(rk4, &Peer(model), model.y0(), tf, RK4_STEPS)
    }
}

mod stiff {
    use super::*;

    #[divan::bench(sample_count = 20)]
    pub fn odyn() -> VanDerPolState {
        odyn_run::<_, ImplicitEuler<_>>(&black_box(VAN_DER_POL), STIFF_DT, STIFF_STEPS)
    }

    #[divan::bench(sample_count = 20)]
    pub fn hand_written() -> [f64; 2] {
        let model = black_box(VAN_DER_POL);
        hand_implicit_euler(&model, model.y0(), STIFF_DT, STIFF_STEPS)
    }

    #[divan::bench(sample_count = 20)]
    pub fn differential_equations() -> [f64; 2] {
        let model = black_box(VAN_DER_POL);
        let euler = ImplicitRungeKutta::backward_euler(STIFF_DT).max_steps(STIFF_STEPS as usize);
        let tf = STIFF_STEPS as f64 * STIFF_DT;
        differential_equations_run(euler, &Peer(model), model.y0(), tf, STIFF_STEPS)
    }
}

// ---------------------------------------------------------------------------------------------
// Agreement.

/// Runs every variant once, prints the final states and asserts that they agree with the
/// hand-written one, in max |Δᵢ| / max |yᵢ|:
///
/// - RK4 to 1e-9: the same method, so the same arithmetic up to rounding (`differential-equations`
///   sums the update as y + (h/6)·k₁ + (h/3)·k₂ + …, the others as y + h/6·(k₁ + 2k₂ + …)).
/// - Implicit Euler to 1e-8: all three solve the same implicit equations each step and differ
///   only where Newton stops — within 1e-10 per step (absolute for `differential-equations`,
///   1e-10·(1 + |y|) for the others), and Newton's last update leaves far less. The stiff
///   component damps such errors by 1/(1 + h·μ(y₁² − 1)) ≈ 1/4 a step and the slow one carries
///   them without growth, so even 100 steps' worth of the full tolerance would pass.
fn check_agreement() {
    agree(
        "lorenz_rk4",
        1e-9,
        &lorenz_rk4::hand_written(),
        &[
            ("odyn", lorenz_rk4::odyn().as_slice()),
            ("ode_solvers", &lorenz_rk4::ode_solvers()),
            (
                "differential_equations",
                &lorenz_rk4::differential_equations(),
            ),
        ],
    );
    agree(
        "spring_rk4",
        1e-9,
        &spring_rk4::hand_written(),
        &[
            ("odyn", spring_rk4::odyn().as_slice()),
            ("ode_solvers", &spring_rk4::ode_solvers()),
            (
                "differential_equations",
                &spring_rk4::differential_equations(),
            ),
        ],
    );
    agree(
        "stiff",
        1e-8,
        &stiff::hand_written(),
        &[
            ("odyn", stiff::odyn().as_slice()),
            ("differential_equations", &stiff::differential_equations()),
        ],
    );
}

/// Prints the final states of a group and asserts each is within `tol` of `reference`.
fn agree(group: &str, tol: f64, reference: &[f64], variants: &[(&str, &[f64])]) {
    let scale = reference.iter().fold(0.0, |m: f64, y| m.max(y.abs()));
    println!("{group}: final states; max |Δ| / max |y| against hand_written (tolerance {tol:.0e})");
    println!("  {:<24}{reference:?}", "hand_written");
    for &(name, y) in variants {
        let diff = y
            .iter()
            .zip(reference)
            .fold(0.0, |m: f64, (a, b)| m.max((a - b).abs()));
        let relative = diff / scale;
        println!("  {name:<24}{y:?}  {relative:.1e}");
        assert!(
            relative <= tol,
            "{group}: {name} differs from hand_written by {relative:.1e}"
        );
    }
}
