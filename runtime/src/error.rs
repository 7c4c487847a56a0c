//! The one error type of the runtime: every failure a user can cause is a variant here.

use std::path::PathBuf;

use crate::Method;

/// Result alias used throughout odyn.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong in a run or while writing its output.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A run-time input was rejected before any step was taken.
    #[error("invalid {field}: {reason}")]
    InvalidInput {
        /// The input that was rejected (`dt`, `steps`, a state component, ...).
        field: String,
        /// Why it was rejected.
        reason: String,
    },
    /// The model itself cannot be integrated: a particle model with a link to a particle that
    /// does not exist, a spring of zero rest length, a particle without mass, ...
    #[error("`{model}` cannot be simulated: {what} {reason}")]
    BadModel {
        /// The model's type name.
        model: &'static str,
        /// The offending part (`springs[12]`, `mass[3]`, `pinned[0]`).
        what: String,
        /// What is wrong with it.
        reason: String,
    },
    /// The chosen method cannot integrate this model.
    #[error("{method} cannot integrate `{model}`: {reason}")]
    Unsupported {
        /// The method asked for.
        method: Method,
        /// The model's type name.
        model: &'static str,
        /// What the method needs that the model lacks.
        reason: &'static str,
    },
    /// The state became non-finite or left the divergence limit.
    #[error(
        "{method} diverged at step {step} (t = {t}): component `{component}` = {value:e} \
         (limit {limit:e}); reduce dt or choose a more stable method"
    )]
    Diverged {
        /// The method that was stepping.
        method: Method,
        /// The first step whose result was rejected (1-based: step 1 maps t0 to t0 + dt).
        step: u64,
        /// Time at the end of that step.
        t: f64,
        /// Name of the first offending state component.
        component: String,
        /// Its value (infinite, NaN or beyond the limit).
        value: f64,
        /// The divergence limit in force.
        limit: f64,
    },
    /// Newton's method did not converge within an implicit step.
    #[error(
        "Newton's method did not converge at t = {t} after {iters} iterations (residual {residual:e}); \
         reduce dt or raise `NewtonOptions::max_iters`"
    )]
    NewtonDidNotConverge {
        /// Time at the end of the step being solved.
        t: f64,
        /// Iterations made.
        iters: u32,
        /// Max-norm of the residual y − y₀ − h·f(t, y) at the last iterate.
        residual: f64,
    },
    /// Reading or writing a file failed.
    #[error("cannot write `{}`: {source}", path.display())]
    Io {
        /// The file odyn was writing.
        path: PathBuf,
        /// The operating-system error.
        source: std::io::Error,
    },
    /// Encoding CSV failed.
    #[error("cannot write CSV `{}`: {source}", path.display())]
    Csv {
        /// The file odyn was writing.
        path: PathBuf,
        /// The CSV encoder's error.
        source: csv::Error,
    },
    /// Drawing a chart failed.
    #[error("cannot draw `{}`: {reason}", path.display())]
    Plot {
        /// The chart file.
        path: PathBuf,
        /// What the plotting backend reported.
        reason: String,
    },
}

impl Error {
    pub(crate) fn invalid(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Error::InvalidInput {
            field: field.into(),
            reason: reason.into(),
        }
    }
}
