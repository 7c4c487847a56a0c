//! The one error type of the runtime: every failure a user can cause is a variant here.

mod advice;

pub use self::advice::{NewtonFailure, Rejection};
pub(crate) use self::advice::{bytes_text, count_text};

use std::path::PathBuf;

use self::advice::{max_steps_advice, projection, step_advice};
use crate::Method;

/// Result alias used throughout odyn.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong in a run or while writing its output.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A fit ([`crate::fit::fit`]) used up its iterations without meeting its tolerances.
    #[error(
        "the fit did not converge in {iterations} iterations (cost {cost:e}); give a closer \
         initial guess, fit log-parameters, or allow more iterations"
    )]
    FitDidNotConverge {
        /// The iterations taken.
        iterations: usize,
        /// ½ Σ wₖ² rₖ² where it stopped.
        cost: f64,
    },
    /// A fit ([`crate::fit::fit`]) cannot start from its initial guess: the model cannot be
    /// solved there, or the cost there is not finite.
    #[error(
        "the fit cannot start from its initial guess ({parameters}): {problem}; give a guess \
         closer to the data, or fit log-parameters (`FitOptions::log_parameters`) so the \
         search moves rates by factors"
    )]
    FitStart {
        /// The guess, `name = value` for each parameter.
        parameters: String,
        /// What failed there.
        problem: String,
    },
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
    /// An event's condition returned NaN (a NaN has no sign, so a crossing there would be missed
    /// without a word), or its change left the state non-finite.
    #[error("event `{event}` at t = {t:?}: {reason}")]
    BadEvent {
        /// The event's name.
        event: String,
        /// Where it happened.
        t: f64,
        /// What was wrong.
        reason: String,
    },
    /// An event fired without end: after a change the state came back to the event's surface
    /// sooner than the event tolerance resolves (its events accumulate at one time — Zeno
    /// behaviour, a ball bouncing ever lower), or the run's events passed
    /// [`crate::RunOptions::max_events`]. Integrating on would pass through the surface.
    #[error("event `{event}` fired {count} times up to t = {t:?}: {reason}")]
    EventsAccumulate {
        /// The event's name.
        event: String,
        /// How often it fired in the run.
        count: u64,
        /// Where the run stopped.
        t: f64,
        /// Which limit was hit, and what to do.
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
    /// The algebraic equations of a differential–algebraic model cannot be satisfied at the
    /// start, or after an event's change, by moving its algebraic components
    /// ([`crate::consistent`]).
    #[error(
        "inconsistent initial values at t = {t:?}: the algebraic equation of `{residual}` has \
         residual {value:e}, and Newton on the algebraic component `{component}` cannot make it \
         zero: {reason}; give initial values that satisfy the algebraic equations, or write \
         each constraint so it depends on its algebraic component (index 1)"
    )]
    InconsistentStart {
        /// Time of the start or the event.
        t: f64,
        /// The algebraic equation (named by its component) with the largest residual.
        residual: String,
        /// |residual| there.
        value: f64,
        /// The algebraic component Newton could not move to satisfy it.
        component: String,
        /// Why.
        reason: &'static str,
    },
    /// The state became non-finite or left the divergence limit.
    #[error(
        "{method} diverged at step {step} (t = {t:?}): component `{component}` = {value:e} \
         (limit {limit:e}); reduce dt or choose a more stable method — or, if values this large \
         are expected, raise the divergence limit"
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
    /// Newton's method did not converge within an implicit step, even on the smallest sub-step
    /// the halving allowed.
    #[error(
        "Newton's method did not converge at t = {t:?} (step {dt:e}, after {halvings} halvings, \
         {iters} iterations, residual {residual:e}): {}",
        cause.explain(*iters, *halvings)
    )]
    NewtonDidNotConverge {
        /// Time at the end of the step being solved.
        t: f64,
        /// The size of that (sub-)step.
        dt: f64,
        /// Iterations made in the last attempt.
        iters: u32,
        /// Max-norm of the residual y − y₀ − h·f(t, y) at the last iterate (NaN when the model
        /// returned NaN).
        residual: f64,
        /// Why the last attempt failed.
        cause: NewtonFailure,
        /// How many times the step was halved before giving up.
        halvings: u32,
    },
    /// An implicit method's Jacobian ∂f/∂y had a NaN or infinite entry at the state its step
    /// started from: the model's derivative there is undefined or overflows (a square root or
    /// logarithm at 0, a power of a negative number, a quotient by zero), and no step size
    /// makes I − γh·J of such a J regular.
    #[error(
        "the Jacobian ∂f/∂y is not finite at t = {t:?}: the derivative of `{row}`'s rate with \
         respect to `{column}` is {value:?}; the model's code has no finite derivative at this \
         state (a square root or logarithm at zero, a power of a negative number, a quotient \
         by zero, an overflow) — check the state and parameters there, or write the code so \
         that its derivative exists"
    )]
    NonFiniteJacobian {
        /// The time of the state.
        t: f64,
        /// The component whose rate's derivative is not finite (J's row).
        row: String,
        /// The component it was taken with respect to (J's column).
        column: String,
        /// The entry: NaN or ±∞.
        value: f64,
    },
    /// The matrix I − c·J of a linearly implicit step was singular (c = γ·h): the step is
    /// retried smaller; past the smallest it is this error.
    #[error(
        "the matrix I − γh·J was singular at t = {t:?} (step {dt:e}): ∂f/∂y has an eigenvalue \
         near 1/(γh); a smaller step avoids it"
    )]
    SingularMatrix {
        /// Start of the step.
        t: f64,
        /// Its size.
        dt: f64,
    },
    /// An adaptive run needed a step smaller than `dt_min` or the resolution of t. What the
    /// message advises follows from the method and from why the last steps were rejected
    /// ([`Rejection`]): an explicit method failing its error test meets stiffness; an implicit
    /// one meets a switch in f that no step resolves, or a solution that blows up.
    #[error(
        "{method} could not take a step at t = {t:?}: the step size fell to {dt:e}, below {}; {}",
        if dt_min >= resolution {
            format!("`dt_min` = {dt_min:e}")
        } else {
            format!("the resolution of t there ({resolution:e}, ten float spacings)")
        },
        step_advice(*method, *rejection, *dt_min >= *resolution, t.abs() >= 1e6)
    )]
    StepSizeTooSmall {
        /// The method that was stepping.
        method: Method,
        /// Where the run stopped.
        t: f64,
        /// The step it would have needed.
        dt: f64,
        /// `AdaptiveOptions::dt_min` in force.
        dt_min: f64,
        /// The smallest step t can take there: ten spacings of floats at t.
        resolution: f64,
        /// Why the last attempt was rejected.
        rejection: Rejection,
    },
    /// An adaptive run used up its step budget (`AdaptiveOptions::max_steps`).
    #[error(
        "{method} took {steps} steps and did not reach the end (stopped at t = {t:?} of \
         {t_end:?}{}): {}",
        projection(*t, *t_end, *mean_step),
        max_steps_advice(*method, *t, *t_end, *mean_step, *steps)
    )]
    MaxSteps {
        /// The method that was stepping.
        method: Method,
        /// Where the run stopped.
        t: f64,
        /// Where the run was to end.
        t_end: f64,
        /// The mean size of the steps it accepted (s; NaN when it accepted none).
        mean_step: f64,
        /// The budget, accepted and rejected steps together.
        steps: u64,
    },
    /// Writing a file failed (reading one is [`Error::Read`]).
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
    /// Reading a file failed: it is missing or cannot be opened. (A file that reads but holds
    /// something other than what odyn wrote is [`Error::InvalidInput`], naming the row.)
    #[error("cannot read `{}`: {source}", path.display())]
    Read {
        /// The file odyn was reading.
        path: PathBuf,
        /// The operating-system error.
        source: std::io::Error,
    },
    /// Shards to merge ([`crate::ensemble::Members::merge`]) that are not every shard of their
    /// ensemble exactly once: some missing (their tasks failed, or their files were not
    /// gathered), or given more than once. Nothing was merged: what is there would be a
    /// silently smaller ensemble.
    #[error("{message}")]
    BadShards {
        /// Members in the whole ensemble.
        members: u64,
        /// The shards it was split into: the n of every shard k/n.
        count: u64,
        /// The k of the shards missing, as ascending ranges (`1..2` is shard 1 alone).
        missing: Vec<std::ops::Range<u64>>,
        /// The k of each shard given more than once, ascending.
        twice: Vec<u64>,
        /// What is wrong, the first few shards by name with their members, and what to run.
        message: String,
    },
    /// A step of one of the solvers beside the ODE runner ([`crate::xpbd::Xpbd`],
    /// [`crate::fluids::StableFluids`]) left its state NaN or infinite: the step was too large
    /// for its forces, or a setting too extreme. The solver's state is left as that step made
    /// it; discard the solver.
    #[error(
        "the state of `{solver}` became non-finite at step {step} (t = {t:?}, dt = {dt:?}): \
         `{component}` = {value:?}; {advice}"
    )]
    NotFinite {
        /// The solver's type name (`Xpbd`, `StableFluids`).
        solver: &'static str,
        /// The step whose result was non-finite, counted from 1 since the solver was made (for
        /// [`crate::fluids::StableFluids::project`] called on its own: the steps before it).
        step: u64,
        /// Time at the end of that step: the sum of the step sizes since the solver was made.
        t: f64,
        /// The size of that step (0 for a projection called on its own).
        dt: f64,
        /// The first non-finite entry (`x[3]`, `v[17]`, `density[40]`).
        component: String,
        /// One of its non-finite values (NaN or ±∞).
        value: f64,
        /// What to change, in the solver's terms.
        advice: &'static str,
    },
}

impl Error {
    /// Whether a driver may retry the step with a smaller size: a failed implicit solve.
    pub(crate) fn is_retriable(&self) -> bool {
        matches!(self, Error::SingularMatrix { .. })
            || matches!(
                self,
                Error::NewtonDidNotConverge {
                    cause: NewtonFailure::Iterations
                        | NewtonFailure::Diverging
                        | NewtonFailure::Singular
                        | NewtonFailure::NotFinite
                        | NewtonFailure::UpdateNotFinite
                        | NewtonFailure::LineSearch,
                    ..
                }
            )
    }

    /// Records how many halvings preceded a final failure.
    pub(crate) fn with_halvings(mut self, depth: u32) -> Self {
        if let Error::NewtonDidNotConverge { halvings, .. } = &mut self {
            *halvings = depth;
        }
        self
    }

    pub(crate) fn invalid(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Error::InvalidInput {
            field: field.into(),
            reason: reason.into(),
        }
    }

    /// A copy of a state that cannot be allocated: `field` and `what` name the state (`grid`,
    /// `is 16384×16384 with 2 fields`), which has `components` values; `smaller` is what to use
    /// instead (`a coarser grid`).
    pub(crate) fn copy_refused(
        field: &str,
        what: String,
        components: usize,
        smaller: &str,
    ) -> Self {
        let bytes = components as u128 * std::mem::size_of::<f64>() as u128;
        Error::invalid(
            field,
            format!(
                "{what}: a copy of its state ({}) cannot be allocated, and a run holds a dozen or \
                 more (the method's stages, the driver's buffers); use {smaller}, or a method \
                 with fewer stages (explicit or symplectic Euler)",
                bytes_text(bytes)
            ),
        )
    }
}

// Parsing a method name fails with an `Error`, so the parser lives with the errors: the table of
// methods (`crate::method`) stays below them.
impl std::str::FromStr for Method {
    type Err = Error;

    /// Parses the snake-case [`Method::name`].
    fn from_str(s: &str) -> Result<Self, Error> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| {
                let names: Vec<_> = Method::ALL.iter().map(|m| m.name()).collect();
                Error::invalid(
                    "method",
                    format!("unknown method `{s}`; supported: {}", names.join(", ")),
                )
            })
    }
}
