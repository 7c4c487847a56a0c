//! [`Simulation`]: configure a run, pick the integrator at run time, record a [`Trajectory`].

use crate::integrators::{
    ExplicitEuler, ImplicitEuler, Integrator, Leapfrog, PositionVerlet, Rk4, SymplecticEuler,
    VelocityVerlet,
};
use crate::stepper::{DEFAULT_DIVERGENCE_LIMIT, check_dt};
use crate::{
    Error, Method, Model, NewtonOptions, Result, Sample, SecondOrder, Stepper, Trajectory,
};

/// How long a run lasts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Length {
    /// Exactly this many steps.
    Steps(u64),
    /// Simulated seconds: ⌈duration/dt⌉ steps (a ratio within 1e-9 of a whole number counts as
    /// that number), so the run ends at or just past `duration`.
    Duration(f64),
}

/// Everything a run needs besides the model and its initial state.
#[derive(Clone, Debug, PartialEq)]
pub struct RunOptions {
    /// The integrator. Default: the model's `#[system(integrator = ...)]`, else [`Method::Rk4`].
    pub method: Method,
    /// The fixed step. Default: the model's `#[system(dt = ...)]`; a run without one is an error.
    pub dt: Option<f64>,
    /// How long to run. Default: none; a run without one is an error.
    pub length: Option<Length>,
    /// Start time (default 0).
    pub t0: f64,
    /// Record every n-th step (default 1); step 0 and the last step are always recorded.
    pub record_every: u64,
    /// |component| beyond which the run counts as diverged (default 1e100).
    pub divergence_limit: f64,
    /// Newton's method in implicit steps (see [`NewtonOptions`] for the defaults).
    pub newton: NewtonOptions,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            method: Method::Rk4,
            dt: None,
            length: None,
            t0: 0.0,
            record_every: 1,
            divergence_limit: DEFAULT_DIVERGENCE_LIMIT,
            newton: NewtonOptions::default(),
        }
    }
}

/// A progress callback: called with (steps done, steps in the run) at every recorded step.
#[derive(Clone, Copy)]
struct Progress<'m>(&'m dyn Fn(u64, u64));

impl std::fmt::Debug for Progress<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Progress(..)")
    }
}

/// A run being configured: created by [`Model::simulate`], finished by [`Simulation::run`].
#[derive(Clone, Debug)]
pub struct Simulation<'m, M: Model> {
    model: &'m M,
    initial: Option<M::State>,
    progress: Option<Progress<'m>>,
    /// The options; the setters below are shorthands for assigning these fields.
    pub options: RunOptions,
}

impl<'m, M: Model> Simulation<'m, M> {
    /// A run of `model` from its own state, with its attribute's method and dt.
    pub fn new(model: &'m M) -> Self {
        let options = RunOptions {
            method: M::DEFAULT_METHOD,
            dt: M::DEFAULT_DT,
            ..RunOptions::default()
        };
        Simulation {
            model,
            initial: None,
            progress: None,
            options,
        }
    }

    /// Uses `method` instead of the attribute's.
    pub fn integrator(mut self, method: Method) -> Self {
        self.options.method = method;
        self
    }

    /// Uses the fixed step `dt`.
    pub fn dt(mut self, dt: f64) -> Self {
        self.options.dt = Some(dt);
        self
    }

    /// Runs exactly `steps` steps.
    pub fn steps(mut self, steps: u64) -> Self {
        self.options.length = Some(Length::Steps(steps));
        self
    }

    /// Runs for `duration` simulated seconds (see [`Length::Duration`]).
    pub fn duration(mut self, duration: f64) -> Self {
        self.options.length = Some(Length::Duration(duration));
        self
    }

    /// Records every `n`-th step.
    pub fn record_every(mut self, n: u64) -> Self {
        self.options.record_every = n;
        self
    }

    /// Starts at time `t0`.
    pub fn start_time(mut self, t0: f64) -> Self {
        self.options.t0 = t0;
        self
    }

    /// Starts from `state` instead of the model's own fields.
    pub fn initial_state(mut self, state: M::State) -> Self {
        self.initial = Some(state);
        self
    }

    /// Sets the divergence limit (see [`RunOptions::divergence_limit`]).
    pub fn divergence_limit(mut self, limit: f64) -> Self {
        self.options.divergence_limit = limit;
        self
    }

    /// Calls `report(done, total)` at every recorded step (see [`Simulation::record_every`]) and
    /// at the end: for a progress bar on long runs. The run's numbers do not depend on it.
    pub fn progress(mut self, report: &'m dyn Fn(u64, u64)) -> Self {
        self.progress = Some(Progress(report));
        self
    }

    /// Uses `newton` for the nonlinear solves of implicit methods.
    pub fn newton(mut self, newton: NewtonOptions) -> Self {
        self.options.newton = newton;
        self
    }

    /// Runs and returns the trajectory.
    ///
    /// Errors: [`Error::InvalidInput`] for bad options or a non-finite initial state,
    /// [`Error::Unsupported`] when the method cannot integrate this model, and
    /// [`Error::Diverged`] when the state blows up (use [`Simulation::run_partial`] to keep the
    /// samples recorded before that).
    pub fn run(&self) -> Result<Trajectory<M::State>> {
        let (trajectory, failure) = self.run_partial()?;
        match failure {
            None => Ok(trajectory),
            Some(error) => Err(error),
        }
    }

    /// Runs and returns the trajectory up to the last good step, with the divergence that
    /// stopped it, if any. Input and capability errors are still `Err`: nothing ran.
    pub fn run_partial(&self) -> Result<(Trajectory<M::State>, Option<Error>)> {
        let plan = self.plan()?;
        let method = self.options.method;
        if method.needs_jacobian() {
            let Some(jacobian) = self.model.as_jacobian() else {
                return Err(self
                    .unsupported("it has no Jacobian (its `#[system]` says `jacobian = false`)"));
            };
            return plan.drive::<_, ImplicitEuler<_>>(jacobian);
        }
        if !method.needs_second_order() {
            return match method {
                Method::ExplicitEuler => plan.drive::<M, ExplicitEuler<_>>(self.model),
                _ => plan.drive::<M, Rk4<_>>(self.model),
            };
        }
        let Some(split) = self.model.as_second_order() else {
            return Err(self.unsupported(
                "it is first-order (`#[state]` fields) and the method needs \
                 `#[position]`/`#[velocity]` fields",
            ));
        };
        if method.needs_velocity_free_forces() && M::SecondOrder::READS_VELOCITY {
            return Err(self.unsupported(
                "its force reads a velocity (in `acceleration`, or a kernel's velocity arguments), \
                 and position Verlet has no velocity to give it; use velocity Verlet or leapfrog",
            ));
        }
        match method {
            Method::SymplecticEuler => plan.drive::<_, SymplecticEuler<_>>(split),
            Method::PositionVerlet => plan.drive::<_, PositionVerlet<_>>(split),
            Method::VelocityVerlet => plan.drive::<_, VelocityVerlet<_>>(split),
            _ => plan.drive::<_, Leapfrog<_>>(split),
        }
    }

    fn unsupported(&self, reason: &'static str) -> Error {
        Error::Unsupported {
            method: self.options.method,
            model: M::NAME,
            reason,
        }
    }

    fn plan(&self) -> Result<Plan<'m, M::State>> {
        let o = &self.options;
        let dt = o.dt.ok_or_else(|| {
            Error::invalid(
                "dt",
                "no step given: call `.dt(..)` or set `#[system(dt = ..)]`",
            )
        })?;
        check_dt(dt)?;
        let steps = match o.length {
            None => {
                return Err(Error::invalid(
                    "length",
                    "no run length given: call `.steps(..)` or `.duration(..)`",
                ));
            }
            Some(Length::Steps(n)) => n,
            Some(Length::Duration(d)) => steps_for(d, dt)?,
        };
        if o.record_every == 0 {
            return Err(Error::invalid("record_every", "must be at least 1"));
        }
        if o.divergence_limit.is_nan() || o.divergence_limit <= 0.0 {
            return Err(Error::invalid(
                "divergence_limit",
                format!("must be positive, got {}", o.divergence_limit),
            ));
        }
        Ok(Plan {
            initial: self.initial.clone().unwrap_or_else(|| self.model.state()),
            dt,
            steps,
            t0: o.t0,
            record_every: o.record_every,
            divergence_limit: o.divergence_limit,
            newton: o.newton,
            progress: self.progress,
        })
    }
}

fn steps_for(duration: f64, dt: f64) -> Result<u64> {
    if !(duration.is_finite() && duration >= 0.0) {
        return Err(Error::invalid(
            "duration",
            format!("must be finite and non-negative, got {duration}"),
        ));
    }
    let ratio = duration / dt;
    let nearest = ratio.round();
    let steps = if (ratio - nearest).abs() <= 1e-9 * nearest.max(1.0) {
        nearest
    } else {
        ratio.ceil()
    };
    if steps > 1e15 {
        return Err(Error::invalid(
            "duration",
            format!("{duration} s at dt = {dt} is {steps:e} steps, more than this runner takes"),
        ));
    }
    Ok(steps as u64)
}

/// A validated run.
struct Plan<'m, S> {
    initial: S,
    dt: f64,
    steps: u64,
    t0: f64,
    record_every: u64,
    divergence_limit: f64,
    newton: NewtonOptions,
    progress: Option<Progress<'m>>,
}

impl<S: crate::State> Plan<'_, S> {
    // One function per integrator: inlined into `run_partial`'s dispatch, the seven run loops
    // shared one body and the cheap ones ran up to 1.7× slower (measured on leapfrog).
    #[inline(never)]
    fn drive<N, I>(self, model: &N) -> Result<(Trajectory<S>, Option<Error>)>
    where
        N: Model<State = S>,
        I: Integrator<N>,
    {
        let mut stepper =
            Stepper::<N, I>::with_newton(model, self.initial, self.t0, self.dt, &self.newton)?
                .with_divergence_limit(self.divergence_limit);
        let capacity = (self.steps / self.record_every + 2).min(1 << 20) as usize;
        let mut samples = Vec::with_capacity(capacity);
        // The recorder gets copies, never `&stepper`: a reference escaping into the (possibly
        // out-of-line) push would pin the stepper's state in memory for the whole loop.
        let record = |step: u64, t: f64, state: S, samples: &mut Vec<Sample<S>>| {
            let energy = model.energy(&state);
            samples.push(Sample {
                step,
                t,
                state,
                energy,
            });
        };
        record(
            stepper.steps(),
            stepper.t(),
            stepper.state().clone(),
            &mut samples,
        );
        let mut failure = None;
        // A countdown, not `n % record_every`: a 64-bit division per step costs more than a
        // cheap model's whole step.
        let mut until_record = self.record_every;
        for n in 1..=self.steps {
            if let Err(error) = stepper.step() {
                failure = Some(error);
                break;
            }
            until_record -= 1;
            if until_record == 0 || n == self.steps {
                record(
                    stepper.steps(),
                    stepper.t(),
                    stepper.state().clone(),
                    &mut samples,
                );
                until_record = self.record_every;
                if let Some(Progress(report)) = self.progress {
                    report(n, self.steps);
                }
            }
        }
        let good_steps = stepper.steps() - u64::from(failure.is_some());
        let evaluations = stepper.evaluations();
        let trajectory = Trajectory {
            model: N::NAME,
            method: I::METHOD,
            dt: self.dt,
            steps: good_steps,
            evaluations: evaluations.force,
            jacobian_evaluations: evaluations.jacobian,
            samples,
        };
        Ok((trajectory, failure))
    }
}
