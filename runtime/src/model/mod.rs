//! The traits `#[system]` implements for a model and the integrators are generic over.
//!
//! A [`Model`] is first-order, y′ = f(t, y). A model with `#[position]`/`#[velocity]` fields is
//! also [`SecondOrder`], q̈ = a(t, q, q̇): its state lays out every position, then every velocity,
//! so the split methods see the two halves of [`State::as_slice`].

pub(crate) mod consistent;
pub mod differences;
pub mod dual;
pub mod flat;
mod jump;
mod mass;
mod parameters;
mod unavailable;

pub use consistent::consistent;
pub use jump::Jump;
pub use mass::Mass;
pub(crate) use mass::mass_of;
pub use parameters::Parameters;
pub use unavailable::Unavailable;

use std::fmt::Debug;

use crate::linalg::NewtonMatrix;
use crate::{Method, Result};

/// A model's state: a list of `f64` components with names.
pub trait State: Clone + PartialEq + Debug {
    /// The components, positions before velocities for second-order models.
    fn as_slice(&self) -> &[f64];
    /// The components, mutably, in the order of [`State::as_slice`].
    fn as_mut_slice(&mut self) -> &mut [f64];
    /// The name of component `index` as CSV headers and errors show it (`x`, `r[1]`).
    fn component_name(&self, index: usize) -> String;

    /// A copy, allocated fallibly: how a run makes its copies of the state (the method's stages,
    /// the driver's buffers, the first sample), so that a state too large for the machine's
    /// memory ends the run with an error rather than aborting the process. Steps copy into
    /// these buffers with `clone_from` and allocate nothing.
    ///
    /// The default clones: a fixed-size state has no heap memory. [`crate::grid::GridState`]
    /// and [`crate::particles::ParticleState`] reserve their values with `try_reserve_exact`.
    ///
    /// Errors: [`crate::Error::InvalidInput`] naming the state's size when the copy cannot be
    /// allocated.
    fn try_clone(&self) -> Result<Self> {
        Ok(self.clone())
    }
}

/// Implemented by the code `#[system]` generates (and the runtime's own wrappers) alone, so
/// [`Model`] — and every trait built on it, [`Parameters`], `ParticleSystem`, `GridSystem` — is
/// sealed: their hidden items are for the generated code, not extension points. Reached as
/// `odyn::__private::Sealed`; not a stable API.
#[doc(hidden)]
pub trait Sealed {}

/// A system of ordinary differential equations, y′ = f(t, y), with optional energy.
///
/// Implemented by `#[system]` alone (the trait is sealed); the runtime never asks a user to write
/// it by hand. What a model
/// can do beyond f(t, y) shows as two capabilities, each an associated type that is `Self` when
/// the model has it and [`Unavailable`] when it does not: [`SecondOrder`] (a position/velocity
/// split, needed by the symplectic methods) and [`Jacobian`] (∂f/∂y, needed by implicit Euler).
#[diagnostic::on_unimplemented(
    message = "`{Self}` is not an odyn model",
    note = "a model is a struct marked `#[system]` and its impl block marked `#[system]`, which \
            defines `fn acceleration` or `fn derivative` (or a particle or field model's \
            kernels)"
)]
pub trait Model: Sealed {
    /// The typed state (`<Model>State`).
    type State: State;
    /// This model as a [`SecondOrder`] one.
    type SecondOrder: SecondOrder<State = Self::State>;
    /// This model as one with a [`Jacobian`].
    type Jacobian: Jacobian<State = Self::State>;
    /// The model's type name, for errors.
    const NAME: &'static str;
    /// The method named by `#[system(integrator = ...)]`, else [`Method::Rk4`].
    const DEFAULT_METHOD: Method;
    /// The step named by `#[system(dt = ...)]`.
    const DEFAULT_DT: Option<f64>;
    /// The relative tolerance named by `#[system(rtol = ...)]`.
    const DEFAULT_RTOL: Option<f64> = None;
    /// The absolute tolerance named by `#[system(atol = ...)]`.
    const DEFAULT_ATOL: Option<f64> = None;
    /// False only for [`Unavailable`], which has no values: the run's dispatch does not
    /// instantiate a method's loop for a capability a model lacks (seven to eleven dead loops per
    /// first-order or Jacobian-less model otherwise).
    #[doc(hidden)]
    const AVAILABLE: bool = true;

    /// The components whose rows of f are algebraic equations 0 = g(t, y, z) rather than rates
    /// (the `#[algebraic]` fields), in the state's layout; empty for an ODE. Their rows and
    /// columns of the mass matrix are zero.
    const ALGEBRAIC: &'static [usize] = &[];
    /// Whether the model is M·y′ = f(t, y) with M ≠ I (algebraic components, or a `fn mass`):
    /// only the methods that take a mass matrix ([`Method::takes_mass_matrix`]) integrate it.
    const MASS_MATRIX: bool = false;

    /// The state held in the model's own fields: the usual initial state.
    fn state(&self) -> Self::State;

    /// The mass matrix M of M·y′ = f(t, y), for states like `state`: the identity with zeros at
    /// [`Model::ALGEBRAIC`] unless the model defines `fn mass`. Built once per run, only for a
    /// model with [`Model::MASS_MATRIX`].
    ///
    /// Errors: [`crate::Error::BadModel`] for a `fn mass` of the wrong size, with a non-finite
    /// entry, or with an entry in an algebraic component's row or column.
    fn mass(&self, state: &Self::State) -> Result<Mass> {
        Mass::identity(Self::NAME, state.as_slice().len(), Self::ALGEBRAIC)
    }

    /// Makes the algebraic components of `y` consistent with the differential ones at `t`
    /// ([`consistent`]); the drivers call it before the first step and after every event that
    /// changes the state. Nothing to do for an ODE.
    ///
    /// Errors: [`crate::Error::InconsistentStart`].
    #[doc(hidden)]
    fn consistent(&self, t: f64, y: &mut Self::State, newton: &crate::NewtonOptions) -> Result<()> {
        let _ = (t, y, newton);
        Ok(())
    }

    /// Writes f(t, y) into `dydt`.
    fn derivative(&self, t: f64, y: &Self::State, dydt: &mut Self::State);

    /// The model's energy at `state`, if it defines `fn energy`.
    fn energy(&self, state: &Self::State) -> Option<f64>;

    /// The model as a [`SecondOrder`] one, if it is.
    fn as_second_order(&self) -> Option<&Self::SecondOrder>;

    /// The model as one with a [`Jacobian`], if it has one.
    fn as_jacobian(&self) -> Option<&Self::Jacobian>;

    /// Checks that the model and `state` can be integrated at all, before any step: particle
    /// models check their topology and masses here. Fixed-size models have nothing to check.
    ///
    /// Errors: [`crate::Error::BadModel`] naming what is wrong.
    fn check(&self, state: &Self::State) -> Result<()> {
        let _ = state;
        Ok(())
    }

    /// Completes the state a change event left, `after` (from `before` at time `t`, changed by
    /// `jump.change`), with what the change cannot know: a
    /// [`crate::sensitivity::Sensitive`] model's sensitivities jump there. The drivers call it
    /// after every change; the default leaves `after` as the change made it.
    ///
    /// Errors: a model's own (a sensitivity jump at a grazing crossing).
    #[doc(hidden)]
    fn complete_change(
        &self,
        t: f64,
        before: &Self::State,
        after: &mut Self::State,
        jump: Jump<'_, Self::State>,
    ) -> Result<()> {
        let _ = (t, before, after, jump);
        Ok(())
    }

    /// The model's own evaluations so far when it is a [`crate::sensitivity::Sensitive`] one,
    /// which a run reports in [`crate::Stats::sensitivity`]; zero (the default) for others.
    #[doc(hidden)]
    fn sensitivity_work(&self) -> crate::SensitivityWork {
        crate::SensitivityWork::default()
    }
}

/// A model with a position/velocity split, q̈ = a(t, q, q̇).
#[diagnostic::on_unimplemented(
    message = "`{Self}` is not a second-order model",
    note = "the symplectic and Verlet methods need `#[position]` and `#[velocity]` fields and \
            `fn acceleration`; a first-order model (`#[state]` fields) runs with the other \
            methods"
)]
pub trait SecondOrder: Model {
    /// Whether `fn acceleration` reads a velocity field (determined by the macro from the body).
    const READS_VELOCITY: bool;

    /// Writes a(t, q, q̇) into the velocity components of `accel`; its position components are
    /// left as they were.
    fn acceleration(&self, t: f64, state: &Self::State, accel: &mut Self::State);
}

/// A model whose Jacobian ∂f/∂y the macro derived exactly from the body of its force function.
#[diagnostic::on_unimplemented(
    message = "`{Self}` has no Jacobian",
    note = "`#[system]` generates one for every model unless it says `jacobian = false`: \
            remove that (or use `jacobian = dual` or `jacobian = finite_differences` for code \
            the macro cannot differentiate), or use a method that does not need one"
)]
pub trait Jacobian: Model {
    /// The Jacobian's type: `SMatrix<f64, N, N>` for a state of N ≤ 32 components,
    /// [`crate::FaerDense`] above that, [`crate::particles::ParticleJacobian`] (sparse, sized at
    /// run time) for particle models.
    type Matrix: NewtonMatrix;
    /// The structural non-zeros (row, column), known at compile time; every other entry of the
    /// Jacobian is zero at every state. Empty when the pattern is not known at compile time:
    /// particle models (it comes from their topology at run time), forward sensitivities, and a
    /// Jacobian of finite differences.
    const NONZEROS: &'static [(usize, usize)];

    /// A Jacobian for states like `state`, every buffer allocated: called once per run.
    fn jacobian_matrix(&self, state: &Self::State) -> Self::Matrix;

    /// Writes ∂f/∂y at (t, y) into `jacobian`, every entry.
    fn jacobian(&self, t: f64, y: &Self::State, jacobian: &mut Self::Matrix);

    /// Whether every entry is exact: `#[system]` sets it false when the model's code calls a
    /// function it cannot see inside (a crate's, or the user's own not marked
    /// `#[odyn::function]`), whose derivative it then takes by a central difference of the
    /// call (relative error ~1e-10 on smooth functions), and for a model that asks for
    /// `jacobian = finite_differences` (central differences of the whole f). Newton-based methods (implicit Euler,
    /// BDF) only iterate with J, so their results do not depend on it; Rosenbrock methods build
    /// it into their stages.
    const EXACT: bool = true;

    /// Whether f reads the time, so ∂f/∂t may be non-zero (false for autonomous models: then
    /// methods that need ∂f/∂t skip it at no cost).
    const TIME_DEPENDENT: bool = true;

    /// Writes ∂f/∂t at (t, y) into `dfdt`.
    ///
    /// `#[system]` generates it exactly from the model's code, or as zero for an autonomous model.
    /// When the time reaches f through code it cannot differentiate (a call of the user's own
    /// function of `t`), this default is used: a central difference
    /// (f(t + h) − f(t − h))/(2h) with h = ε^⅓·max(1, |t|), accurate to about 1e-10 relative,
    /// which allocates one state per call.
    fn time_derivative(&self, t: f64, y: &Self::State, dfdt: &mut Self::State) {
        let h = crate::math::Transcendental::cbrt(f64::EPSILON) * t.abs().max(1.0);
        let mut minus = y.clone();
        self.derivative(t + h, y, dfdt);
        self.derivative(t - h, y, &mut minus);
        for (d, m) in dfdt.as_mut_slice().iter_mut().zip(minus.as_slice()) {
            *d = (*d - m) / (2.0 * h);
        }
    }
}

/// Positions and velocities of a second-order state: the two halves of its components.
#[inline(always)]
pub(crate) fn split(s: &[f64]) -> (&[f64], &[f64]) {
    s.split_at(s.len() / 2)
}

/// Mutable [`split`].
#[inline(always)]
pub(crate) fn split_mut(s: &mut [f64]) -> (&mut [f64], &mut [f64]) {
    let half = s.len() / 2;
    s.split_at_mut(half)
}
