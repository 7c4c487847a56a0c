//! odyn: declarative ODE, particle and grid simulation with typed state and measured integrators.
//!
//! Annotate a model struct with [`system`], write its force (or derivative) and energy in plain
//! Rust in an impl block also marked `#[system]`, and run it:
//!
//! ```
//! use odyn::prelude::*;
//!
//! /// Damped spring, m·ẍ = −k·x − b·ẋ.
//! #[system(integrator = SymplecticEuler, dt = 0.016)]
//! pub struct Spring {
//!     #[position] pub x: f64,
//!     #[velocity] pub v: f64,
//!     pub k: f64,
//!     pub b: f64,
//!     pub m: f64,
//! }
//!
//! #[system]
//! impl Spring {
//!     fn acceleration(&self) -> f64 { (-self.k * self.x - self.b * self.v) / self.m }
//!     fn energy(&self) -> f64 { 0.5 * self.m * self.v * self.v + 0.5 * self.k * self.x * self.x }
//! }
//!
//! # fn main() -> odyn::Result<()> {
//! let spring = Spring { x: 1.0, v: 0.0, k: 50.0, b: 0.5, m: 1.0 };
//! let run = spring.simulate().duration(10.0).run()?; // the attribute's method and dt
//! assert_eq!(run.steps(), 625);
//! let SpringState { x, v } = run.last().state; // the generated typed state
//! assert!(x.abs() < 1.0 && v.abs() < 10.0);
//! # Ok(())
//! # }
//! ```
//!
//! # Where to read on
//!
//! - **The guide**, `docs/book/` in the repository (`mdbook serve docs/book`): one chapter per
//!   topic — models, running, integrators, adaptive stepping and events, Jacobians, stiff
//!   problems, linear solvers, fitting, stability, ensembles, determinism, particles, fields,
//!   constraints and fluids. Every example in it is compiled and run by `cargo test`.
//! - **The attribute's reference**: [`system`] (arguments, model kinds, generated items, and the
//!   Rust the generated Jacobian follows) and [`function`] (helper functions).
//! - **The runtime**, re-exported here: [`Simulation`] (a run's options) and [`Trajectory`] (what
//!   it returns), [`Method`] (the integrators; one file each under [`integrators`]),
//!   [`Model`], [`SecondOrder`], [`Jacobian`] and [`Parameters`] (what `#[system]` implements),
//!   [`Error`] (every failure, typed), [`NewtonOptions`] and [`LinearSolver`] (implicit
//!   solves), [`stability`] and [`work_precision`] (measuring a method on a model),
//!   [`sensitivity`] and [`fit`], [`ensemble`], [`particles`], [`grid`], [`xpbd`], [`sph`],
//!   [`fluids`], [`plot`] and [`output`].
//! - **Benchmarks**: `BENCHMARKS.md` in the repository, each table with the command that
//!   regenerates it.
//!
//! # Features
//!
//! - `plot` (default): PNG/SVG charts with plotters and a bundled font ([`plot`]).
//! - `deterministic`: bit-identical runs across platforms; every transcendental function odyn
//!   and the generated code call goes through the pure-Rust `libm` crate ([`math`]).

#[doc(inline)]
#[doc = include_str!("system.md")]
pub use odyn_macros::system;

/// Marks a helper function of a model, which [`system`] reads and differentiates wherever the
/// force calls it.
///
/// A helper is a method of the model's `#[system]` impl block: `fn restoring(&self, x: f64) -> f64`
/// (reading parameters as `self.k`) or `fn drag(b: f64, v: f64) -> f64` (no receiver), called
/// on the state as `self.restoring(self.x)` or `Self::drag(self.b, self.v)`. The macro inlines
/// its body into the expression graph at each call, so the Jacobian is exact through it and
/// through the helpers it calls; at run time the force calls it as the ordinary method it stays.
///
/// - It takes numbers (`f64`, `[f64; N]`, `VectorN<f64>`, `SVector<f64, N>`, by value or `&`)
///   and returns one or a tuple of them.
/// - Its body may use everything the force's may; its problems are reported at its own tokens.
/// - It reads the state only through its arguments (`self.x` inside it is refused: odyn calls it
///   at states other than the struct's own), and may not call itself, directly or through other
///   helpers (inlining would never end).
/// - It works in particle kernels and cell methods too, and under `jacobian = dual` it gets a
///   dual-number copy.
///
/// ```
/// use odyn::prelude::*;
///
/// /// Duffing oscillator with quadratic drag: ẍ = −x − c·x³ − b·ẋ·|ẋ|.
/// #[system]
/// pub struct Duffing { #[position] pub x: f64, #[velocity] pub v: f64, pub c: f64, pub b: f64 }
///
/// #[system]
/// impl Duffing {
///     fn acceleration(&self) -> f64 { self.restoring(self.x) + Self::drag(self.b, self.v) }
///
///     #[odyn::function]
///     fn restoring(&self, x: f64) -> f64 { -x - self.c * x.powi(3) }
///
///     #[odyn::function]
///     fn drag(b: f64, v: f64) -> f64 { -b * v * v.abs() }
/// }
///
/// let duffing = Duffing { x: 2.0, v: -0.5, c: 40.0, b: 0.2 };
/// let mut j = duffing.jacobian_matrix(&duffing.state());
/// duffing.jacobian(0.0, &duffing.state(), &mut j);
/// assert_eq!(j[(1, 0)], -1.0 - 3.0 * 40.0 * 4.0); // through `restoring`
/// assert_eq!(j[(1, 1)], -2.0 * 0.2 * 0.5);        // through `drag`
/// ```
///
/// Written anywhere else — on a free function, in another impl block — it is a compile error
/// asking for the helper to be moved into the model's impl block: an attribute sees only its own
/// item, so `#[system]` could not read a body written elsewhere.
///
/// ```compile_fail
/// // error: `#[odyn::function]` marks a helper of a model, read by `#[system]`: move `cubic`
/// // into the model's `#[system]` impl block …
/// #[odyn::function]
/// fn cubic(x: f64) -> f64 { x * x * x }
/// ```
#[doc(inline)]
pub use odyn_macros::function;

pub use odyn_runtime::*;

// `#[macro_export]` puts the runtime's macros for generated code at its root, where the glob
// above would re-export them as `odyn::__flat_state` and the like. These private imports shadow
// them (a name imported by name outranks a glob), so only `odyn::__private` reaches them.
#[allow(unused_imports, hidden_glob_reexports)]
use odyn_runtime::{__flat_state, __generic_flat_state, __state_arithmetic};

/// What code generated by `#[system]` refers to; not a stable API.
///
/// The macros it holds are reachable nowhere else in `odyn`:
///
/// ```compile_fail
/// // error[E0603]: macro import `__flat_state` is private
/// use odyn::__flat_state;
/// ```
#[doc(hidden)]
pub mod __private {
    pub use odyn_macros::__system_impl as system_impl;
    pub use odyn_runtime::__private::*;
}

/// The names a model file needs: `use odyn::prelude::*;`.
pub mod prelude {
    pub use crate::grid::{Boundary, Grid, Stencil};
    pub use crate::nalgebra::{SVector, Vector1, Vector2, Vector3, Vector4, Vector5, Vector6};
    pub use crate::particles::ParticleSystem;
    pub use crate::{
        Direction, Error, Event, Jacobian, Method, Model, NewtonOptions, Result, SecondOrder,
        Simulate, Simulation, State, Stepping, Tolerances, Trajectory, method, system,
    };
}

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

/// The guide's chapters, compiled and run as doctests (see the module).
#[cfg(any(test, doctest))]
mod guide;
