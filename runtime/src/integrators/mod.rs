//! The integrators, one per file, each generic over the model it steps.
//!
//! | method | order | f evals/step | error estimate | dense output | energy on an oscillator | needs |
//! |---|---|---|---|---|---|---|
//! | [`ExplicitEuler`] | 1 | 1 | — | Hermite (3) | grows ×(1 + ω²dt²) per step | f(t, y) |
//! | [`SymplecticEuler`] | 1 | 1 | — | Hermite (3) | bounded, E/E₀ ∈ [2/(2+ωdt), 2/(2−ωdt)] | q/v split |
//! | [`PositionVerlet`] | 2 | 1 | — | Hermite (3) | bounded, E/E₀ ∈ [1 − ω²dt²/4, 1] | split, forces free of v |
//! | [`VelocityVerlet`] | 2 | 1 (reused) | — | Hermite (3) | bounded, as position Verlet | split |
//! | [`Leapfrog`] | 2 | 1 (reused) | — | Hermite (3) | bounded, as position Verlet | split |
//! | [`Yoshida4`] | 4 | 3 (reused) | — | Hermite (3) | bounded | split, forces free of v |
//! | [`Yoshida6`] | 6 | 7 (reused) | — | Hermite (3) | bounded | split, forces free of v |
//! | [`KahanLi6`] | 6 | 9 (reused) | — | Hermite (3) | bounded | split, forces free of v |
//! | [`Rk4`] | 4 | 4 | — | Hermite (3) | slow secular decay | f(t, y) |
//! | [`ImplicitEuler`] | 1 | Newton: ≥ 2 f and 2 ∂f/∂y | — | Hermite (3) | decays ×1/(1 + ω²dt²) per step | ∂f/∂y |
//! | [`Tsit5`] | 5 | 6 (FSAL) | order 4 | own, order 4 | slow drift, set by the tolerance | f(t, y) |
//! | [`Dop853`] | 8 | 12 (FSAL) | orders 5 and 3 | own, order 7 (3 more f) | slow drift, set by the tolerance | f(t, y) |
//! | [`Rosenbrock23`] | 2 | 2 (FSAL), 1 J, 1 LU, 3 solves | order 3 | own, order 2 | damped (L-stable) | ∂f/∂y, ∂f/∂t |
//! | [`Rodas5P`] | 5 | 8, 1 J, 1 LU, 8 solves | order 4 | own, order 4 | damped (L-stable) | ∂f/∂y, ∂f/∂t |
//! | [`Bdf`] | 1–5 (2 at a fixed step) | 2–4 (Newton; 1–3 on particle and field models); J and LU kept across steps | order k + 1 difference | own, order k | damped (orders 1–2 A-stable) | ∂f/∂y |
//!
//! Stability on an undamped oscillator of angular frequency ω: the split methods are stable for
//! ω·dt < 2, RK4 for ω·dt < 2√2, explicit Euler for no dt at all, implicit Euler and the
//! Rosenbrock methods for every dt.
//!
//! # The shape every method shares
//!
//! A method only computes: [`Integrator::attempt`] takes one step of a given size from a given
//! state into a separate buffer and returns its error estimate, if it has one. The drivers in
//! `crate::drive` decide everything else — the fixed grid or the adaptive step-size control,
//! halving a step whose implicit solve failed, events, dense output, recording, statistics — once
//! for every method. A method that reuses work between steps (the last force of the Verlet family,
//! the first-same-as-last stage of Tsit5 and DOP853) keeps it when the driver calls
//! [`Integrator::accept`], so a rejected attempt costs nothing to undo, and forgets it on
//! [`Integrator::restart`] when an event changes the state.
//!
//! An integrator is created once per run by [`Integrator::start`], which allocates its scratch
//! states; attempts then allocate nothing.

mod composition;
mod dense_step;
mod explicit_rk;
mod linearization;
mod rosenbrock;
mod tableaux;
mod verlet;

pub use composition::{Composed, Composition, Weights};
pub use dense_step::DenseStep;
pub use dop853::Dop853Tableau;
pub use explicit_rk::{ExplicitRk, Tableau};
pub use implicit_euler::QuasiNewton;
pub use kahan_li6::KahanLi6Weights;
pub use leapfrog::LeapfrogForm;
pub use linearization::Linearization;
pub use rodas5p::Rodas5PTableau;
pub use rosenbrock::{Rosenbrock, RosenbrockTableau};
pub use rosenbrock23::Rosenbrock23Tableau;
pub use tsit5::Tsit5Tableau;
pub use velocity_verlet::VelocityVerletForm;
pub use verlet::{Verlet, VerletForm};
pub use yoshida4::Yoshida4Weights;
pub use yoshida6::Yoshida6Weights;

/// How the stability explorer predicts a method's limit (the `stability` column of the table of
/// methods): from the stability polynomial of an explicit Runge–Kutta method, ω·dt < 2 for the
/// Verlet family, from a composition's weights, or any dt on a left-half-plane spectrum.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum StabilityRule {
    RungeKutta,
    Verlet,
    Composition,
    AStable,
}

/// Declares every integrator's module (`mod <module>; pub use <module>::<Variant>;`) and the
/// per-method stability facts from the one table of methods (`odyn_methods::for_each_method!`).
macro_rules! declare_integrators {
    (
        []
        $(
            $(#[$doc:meta])* $variant:ident $module:ident $name:literal $label:literal
            $order:literal $adaptive:literal $needs:ident $stability:ident;
        )*
    ) => {
        $(
            mod $module;
            pub use $module::$variant;
        )*

        /// The rule the stability explorer predicts `method`'s limit by.
        pub(crate) const fn stability_rule(method: Method) -> StabilityRule {
            match method {
                $(Method::$variant => StabilityRule::$stability,)*
            }
        }

        /// The coefficients γⱼ of the stability polynomial R(z) = Σⱼ γⱼ zʲ of an explicit
        /// Runge–Kutta method, from its module's `tableau_polynomial()` (Hairer & Wanner,
        /// *Solving ODEs II*, §IV.2, eq. (2.4)); empty for methods that are not explicit
        /// Runge–Kutta methods.
        pub(crate) fn tableau_polynomial(method: Method) -> Vec<f64> {
            match method {
                $(Method::$variant => declare_integrators!(@polynomial $stability $module),)*
            }
        }

        /// The largest ω·h for which a composition method is stable on ẍ = −ω²x, from its
        /// module's `Substeps` weights (0 for other methods).
        pub(crate) fn composition_limit(method: Method) -> f64 {
            match method {
                $(Method::$variant => declare_integrators!(@composition $stability $module),)*
            }
        }
    };
    (@polynomial RungeKutta $module:ident) => { $module::tableau_polynomial() };
    (@polynomial $other:ident $module:ident) => { Vec::new() };
    (@composition Composition $module:ident) => {
        composition::oscillator_limit(<$module::Substeps as Weights>::WEIGHTS)
    };
    (@composition $other:ident $module:ident) => { 0.0 };
}

odyn_methods::for_each_method!(declare_integrators);

/// The coefficients of R(z) from an explicit tableau: γⱼ = bᵀAʲ⁻¹𝟙 (γ₀ = 1).
pub(crate) fn polynomial_from_tableau<const S: usize>(a: &[[f64; S]; S], b: &[f64; S]) -> Vec<f64> {
    let mut v = [1.0; S];
    let mut gamma = vec![1.0];
    for _ in 0..S {
        gamma.push(b.iter().zip(&v).map(|(bi, vi)| bi * vi).sum());
        v = std::array::from_fn(|i| a[i].iter().zip(&v).map(|(aij, vj)| aij * vj).sum());
    }
    gamma
}

use crate::{Controller, Method, Model, NewtonOptions, Result, State, Stats, Tolerances};

mod sealed {
    /// Implemented by odyn's own methods and their coefficient types alone, so
    /// [`Integrator`](super::Integrator), [`Tableau`](super::Tableau),
    /// [`RosenbrockTableau`](super::RosenbrockTableau), [`VerletForm`](super::VerletForm) and
    /// [`Weights`](super::Weights) are sealed: each names its [`Method`](crate::Method), a
    /// variant of the closed table of methods, so a type from outside could not run.
    pub trait Sealed {}
}
use sealed::Sealed;

/// One integration method, specialised to a model. Sealed: the methods are the table's.
pub trait Integrator<M: Model>: Sized + Sealed {
    /// The [`Method`] this integrator implements.
    const METHOD: Method;
    /// Degree of the polynomial [`Integrator::dense`] fills (3 for the cubic Hermite interpolant
    /// the drivers use for methods without their own).
    const DENSE_DEGREE: usize = 3;
    /// The step-size controller of adaptive runs (methods without an error estimate never use
    /// it).
    const CONTROLLER: Controller = Controller::dopri5(4);
    /// The order Hairer's algorithm sizes the first step of an adaptive run for: the method's
    /// own, or the one a variable-order method starts at (1 for [`Bdf`]).
    const START_ORDER: u32 = Self::METHOD.order();

    /// Checks the model, the state and the options, then [`prepare`](Integrator::prepare)s the
    /// method: how every run begins, and how code that drives an integrator by hand must begin.
    ///
    /// Errors: [`crate::Error::BadModel`] when [`Model::check`] fails (a particle model's link to
    /// a particle that does not exist); [`crate::Error::InvalidInput`] for a non-finite initial
    /// state, bad [`NewtonOptions`], or scratch states that cannot be allocated
    /// ([`State::try_clone`]); an implicit method's linear solver that cannot be set up.
    fn start(
        model: &M,
        t0: f64,
        y0: &M::State,
        newton: &NewtonOptions,
        stats: &mut Stats,
    ) -> Result<Self> {
        check_start(model, y0, newton)?;
        Self::prepare(model, t0, y0, newton, stats)
    }

    /// Allocates scratch states like `y0` (fallibly, [`State::try_clone`]) and makes any
    /// start-up evaluation (the Verlet family's first force), counted in `stats`; `newton`
    /// configures the nonlinear solve of implicit methods and is ignored by explicit ones. Called
    /// by [`Integrator::start`] after its checks; call that instead.
    ///
    /// Errors: [`crate::Error::InvalidInput`] when a scratch state cannot be allocated; an
    /// implicit method whose linear solver cannot be set up.
    fn prepare(
        model: &M,
        t0: f64,
        y0: &M::State,
        newton: &NewtonOptions,
        stats: &mut Stats,
    ) -> Result<Self>;

    /// Attempts one step of size `h` from (`t`, `y`), writing the result into `y_new`; `y` is not
    /// changed, so a rejected attempt needs no undoing. Returns the error norm of the step
    /// against `tolerances` (accept when ≤ 1), or 0 when the method has no error estimate or no
    /// tolerances are given.
    ///
    /// Errors: an implicit method whose solve failed ([`crate::Error::NewtonDidNotConverge`],
    /// [`crate::Error::SingularMatrix`]); the driver may retry with a smaller step.
    fn attempt(&mut self, model: &M, step: Step<'_, M::State>, y_new: &mut M::State)
    -> Result<f64>;

    /// The last attempt was accepted: keep what it computed that the next step reuses.
    #[inline]
    fn accept(&mut self) {}

    /// The size the method wants for its next step, if it chooses its step sizes itself; `None`
    /// (the default) leaves them to the driver's [`Controller`], which sizes steps from the
    /// error norm alone.
    ///
    /// A method whose step size and order are chosen together ([`Bdf`]) proposes them here. The
    /// adaptive driver asks after every attempt — after [`Integrator::accept`] for an accepted
    /// step, after [`Integrator::attempt`] for one its error norm rejected (above 1) or whose
    /// solve failed — and still caps the step at `dt_max` and shortens it to land on the end and
    /// on time events; the method takes whatever step it is then given. Fixed-step runs ignore
    /// it.
    #[inline]
    fn next_step(&self) -> Option<f64> {
        None
    }

    /// The sparse factorizations and Krylov solves of this integrator's Newton matrix so far, for
    /// [`Stats::linear`]; zero (the default) for explicit methods and dense models.
    #[inline]
    fn linear_work(&self) -> crate::LinearWork {
        crate::LinearWork::default()
    }

    /// A copy of this integrator, if it can be copied cheaply (`None`, the default, when not).
    /// Fixed-step runs step small plain integrators in a local copy, which the optimiser keeps in
    /// registers as it would a hand-written loop's variables.
    #[inline]
    fn duplicate(&self) -> Option<Self> {
        None
    }

    /// Takes one step of size `h` from (`t`, `y`) in place and accepts it whatever its error
    /// estimate, `scratch` holding the new state while it is computed: a bare fixed-step loop,
    /// for code that drives a method by hand ([`crate::Stepper`] adds step halving and the
    /// divergence check).
    ///
    /// Errors: as [`Integrator::attempt`]; `y` is then unchanged.
    #[inline]
    fn step(
        &mut self,
        model: &M,
        t: f64,
        h: f64,
        y: &mut M::State,
        scratch: &mut M::State,
        stats: &mut Stats,
    ) -> Result<()> {
        let step = Step {
            t,
            h,
            y,
            tolerances: None,
            stats,
        };
        self.attempt(model, step, scratch)?;
        self.accept();
        std::mem::swap(y, scratch);
        Ok(())
    }

    /// The state was changed from outside at `t` (an event's action): forget what was reused and
    /// re-evaluate it at the new state.
    fn restart(&mut self, model: &M, t: f64, y: &M::State, stats: &mut Stats) {
        let _ = (model, t, y, stats);
    }

    /// Fills `dense` with the method's own continuous extension of the last accepted step, from
    /// (t, y) to (t + h, y_new); returns false when the method has none (the driver then uses
    /// the cubic Hermite interpolant).
    fn dense(
        &mut self,
        model: &M,
        step: Step<'_, M::State>,
        y_new: &M::State,
        dense: &mut DenseStep<M::State>,
    ) -> bool {
        let _ = (model, step, y_new, dense);
        false
    }
}

/// The checks every run begins with ([`Integrator::start`]'s, made once per run by the drivers,
/// which then `prepare` the method): a finite initial state, valid Newton options and the
/// model's own [`Model::check`].
pub(crate) fn check_start<M: Model>(
    model: &M,
    y0: &M::State,
    newton: &NewtonOptions,
) -> Result<()> {
    if let Some((index, value)) = crate::checks::first_outside(y0, f64::MAX) {
        return Err(crate::Error::invalid(
            format!("initial state `{}`", y0.component_name(index)),
            format!("must be finite, got {value:?}"),
        ));
    }
    newton.check()?;
    model.check(y0)
}

/// `N` copies of `y`, each allocated fallibly ([`State::try_clone`]): an integrator's stages.
pub(crate) fn copies<S: State, const N: usize>(y: &S) -> Result<[S; N]> {
    let mut copies = Vec::with_capacity(N);
    for _ in 0..N {
        copies.push(y.try_clone()?);
    }
    Ok(copies
        .try_into()
        .unwrap_or_else(|_| unreachable!("exactly N copies were made")))
}

/// One step as the driver asks for it.
pub struct Step<'a, S> {
    /// Start time.
    pub t: f64,
    /// Step size.
    pub h: f64,
    /// State at `t`.
    pub y: &'a S,
    /// Tolerances of an adaptive run; `None` at a fixed step (no error estimate is needed).
    pub tolerances: Option<&'a Tolerances>,
    /// Where the method counts its evaluations.
    pub stats: &'a mut Stats,
}

impl<S> Step<'_, S> {
    /// A shorter borrow of the same step, for passing on.
    #[inline]
    pub fn reborrow(&mut self) -> Step<'_, S> {
        Step {
            t: self.t,
            h: self.h,
            y: self.y,
            tolerances: self.tolerances,
            stats: self.stats,
        }
    }
}

/// y ← y + a·x.
#[inline(always)]
fn axpy(y: &mut [f64], a: f64, x: &[f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += a * xi;
    }
}

/// out ← y + a·x.
#[inline(always)]
fn set_axpy(out: &mut [f64], y: &[f64], a: f64, x: &[f64]) {
    for ((oi, yi), xi) in out.iter_mut().zip(y).zip(x) {
        *oi = yi + a * xi;
    }
}
