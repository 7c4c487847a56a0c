//! [`MethodType`]: a method chosen at compile time, for [`Simulation::run_with`].

use std::fmt;

use crate::{Error, Method, Model, Result, Simulation, Trajectory};

/// A method chosen at compile time: one zero-sized type per [`Method`] in [`crate::method`],
/// named like its variant ([`crate::method::Rk4`] for [`Method::Rk4`]).
///
/// [`Simulation::run_with::<T>()`](Simulation::run_with) runs a model with `T` and compiles
/// only `T`'s loop for it; [`Simulation::run`] reads the [`Method`] at run time and so compiles
/// every method the model can take. Choose the typed form in programs that run a model with
/// methods known when they are written; keep [`Method`] for command lines, configuration files
/// and comparisons over many methods. Sealed: the methods are the table's.
pub trait MethodType: Sealed + Copy + Default + fmt::Debug + Send + Sync + 'static {
    /// The method's variant of the run-time enum.
    const METHOD: Method;
}

/// Only the table's methods are [`MethodType`]s; each drives its integrator type (implemented
/// by the run's dispatch, `plan`). Public in name only: this module is private.
pub trait Sealed {
    /// Runs `simulation` with this method on the current stack.
    fn run<M: Model>(
        simulation: &Simulation<'_, M>,
    ) -> Result<(Trajectory<M::State>, Option<Error>)>;
}
