//! The validated run and its dispatch: a [`Plan`] drives the method's integrator type on the
//! model, its second-order split or its Jacobian.

use super::Simulation;
use super::options::Span;
use super::typed::{MethodType, Sealed};
use crate::drive::{Driver, Recording, Start, Track};
use crate::integrators::Integrator;
use crate::method;
use crate::{Error, Method, Model, Result, SecondOrder, State, Stepping, Trajectory};

/// The run's dispatch from the one table of methods: each method's type in [`crate::method`]
/// drives its integrator type (same name, in [`crate::integrators`]) on the model, its
/// second-order split or its Jacobian, as the row's `needs` says; the run-time [`Method`]
/// matches to the type. Exhaustive by construction.
macro_rules! dispatch {
    (
        []
        $(
            $(#[$doc:meta])* $variant:ident $module:ident $name:literal $label:literal
            $order:literal $adaptive:literal $needs:ident $stability:ident;
        )*
    ) => {
        $(
            impl MethodType for method::$variant {
                const METHOD: Method = Method::$variant;
            }

            impl Sealed for method::$variant {
                fn run<M: Model>(
                    run: &Simulation<'_, M>,
                ) -> Result<(Trajectory<M::State>, Option<Error>)> {
                    let plan = run.plan(Method::$variant)?;
                    dispatch!(@drive $needs run plan $variant)
                }
            }
        )*

        impl<M: Model> Simulation<'_, M> {
            /// [`Simulation::run_partial`] on the current stack, with the method of the options.
            pub(super) fn run_here(&self) -> Result<(Trajectory<M::State>, Option<Error>)> {
                match self.options.integrator {
                    $(Method::$variant => <method::$variant as Sealed>::run(self),)*
                }
            }
        }
    };
    (@drive Nothing $run:ident $plan:ident $variant:ident) => {
        $plan.drive::<M, crate::integrators::$variant<_>>($run.model)
    };
    (@drive Split $run:ident $plan:ident $variant:ident) => {
        dispatch!(@capable SecondOrder $run $plan $variant $run.split(Method::$variant)?)
    };
    (@drive VelocityFree $run:ident $plan:ident $variant:ident) => {
        dispatch!(@capable SecondOrder $run $plan $variant $run.split(Method::$variant)?)
    };
    (@drive Jacobian $run:ident $plan:ident $variant:ident) => {
        dispatch!(@capable Jacobian $run $plan $variant $run.jacobian(Method::$variant)?)
    };
    // `model` is the capability, which `split`/`jacobian` return only when the model has it:
    // for `Unavailable` (no values) they return the error, so the `else` is never taken; the
    // constant condition keeps the method's loop from being compiled for `Unavailable` at all.
    (@capable $capability:ident $run:ident $plan:ident $variant:ident $model:expr) => {{
        let model = $model;
        if const { <M::$capability as Model>::AVAILABLE } {
            $plan.drive::<_, crate::integrators::$variant<_>>(model)
        } else {
            Err($run.unsupported(Method::$variant, "it lacks the capability the method needs"))
        }
    }};
}

odyn_methods::for_each_method!(dispatch);

impl<'m, M: Model> Simulation<'m, M> {
    /// The model as a second-order one, checked against what the method needs.
    fn split(&self, method: Method) -> Result<&'m M::SecondOrder> {
        let Some(split) = self.model.as_second_order() else {
            return Err(self.unsupported(
                method,
                "it is first-order (`#[state]` fields) and the method needs \
                 `#[position]`/`#[velocity]` fields",
            ));
        };
        if method.needs_velocity_free_forces() && M::SecondOrder::READS_VELOCITY {
            return Err(self.unsupported(
                method,
                "its force reads a velocity (in `acceleration`, or a kernel's velocity arguments), \
                 and the method evaluates forces at positions only (position Verlet, the leapfrog \
                 compositions); use velocity Verlet or leapfrog",
            ));
        }
        Ok(split)
    }

    /// The model with its Jacobian.
    fn jacobian(&self, method: Method) -> Result<&'m M::Jacobian> {
        self.model.as_jacobian().ok_or_else(|| {
            self.unsupported(
                method,
                "it has no Jacobian (its `#[system]` says `jacobian = false`)",
            )
        })
    }

    fn unsupported(&self, method: Method, reason: &'static str) -> Error {
        Error::Unsupported {
            method,
            model: M::NAME,
            reason,
        }
    }

    /// The run with `method`, its options checked against its initial state.
    fn plan(&self, method: Method) -> Result<Plan<'_, 'm, M>> {
        let initial = match &self.initial {
            Some(initial) => initial.try_clone()?,
            None => self.model.state(),
        };
        let checked = self.options.check(
            method,
            self.stepping_for(method),
            initial.as_slice(),
            &|reason| self.unsupported(method, reason),
        )?;
        Ok(Plan {
            initial,
            span: checked.span,
            simulation: self,
            limit: checked.limit,
            dense: checked.dense,
        })
    }
}

/// A validated run.
struct Plan<'s, 'm, M: Model> {
    initial: M::State,
    span: Span,
    simulation: &'s Simulation<'m, M>,
    limit: f64,
    dense: bool,
}

impl<'s, M: Model> Plan<'s, '_, M> {
    /// The run's track on `model` (the model itself, or its split or Jacobian), for a method
    /// whose interpolant has `dense_degree`; generic over the model only.
    fn start<'n, N: Model<State = M::State>>(
        self,
        model: &'n N,
        dense_degree: usize,
        method: Method,
    ) -> Result<(Track<'s, 'n, N>, Span)> {
        let o = &self.simulation.options;
        let recording = Recording {
            every: o.record_every,
            save_at: o.save_at.as_deref(),
            dense: self.dense,
            progress: self.simulation.progress.map(|p| p.0),
        };
        let start = Start {
            t0: o.t0,
            newton: &o.newton,
            limit: self.limit,
            event_options: (o.event_tolerance, o.max_events),
            dense_degree,
            method,
        };
        let events = self.simulation.events.clone();
        let track = Track::new(model, self.initial, start, events, recording)?;
        Ok((track, self.span))
    }

    // One function per integrator: inlined into `run_partial`'s dispatch, the run loops shared
    // one body and the cheap ones ran up to 1.7× slower (measured on leapfrog).
    #[inline(never)]
    fn drive<N, I>(self, model: &N) -> Result<(Trajectory<M::State>, Option<Error>)>
    where
        N: Model<State = M::State>,
        I: Integrator<N>,
    {
        let simulation = self.simulation;
        let o = &simulation.options;
        let sensitivity = model.sensitivity_work();
        let (track, span) = self.start(model, I::DENSE_DEGREE, I::METHOD)?;
        let mut driver = Driver::<N, I>::on(track, &o.newton)?;
        let outcome = match &span {
            Span::Fixed { dt, steps } => driver.run_fixed(*dt, 0, *steps),
            // A method without an error estimate never gets here (`Options::check` refuses
            // tolerances for it): the constant keeps the adaptive loop from being compiled for
            // the fixed-step methods.
            Span::Adaptive { tolerances, t_end } => {
                if const { I::METHOD.is_adaptive() } {
                    driver.run_adaptive(
                        *t_end,
                        tolerances,
                        &o.adaptive,
                        I::CONTROLLER,
                        I::START_ORDER,
                    )
                } else {
                    Err(simulation.unsupported(I::METHOD, "it cannot step to tolerances"))
                }
            }
        };
        let mut track = driver.into_track();
        track.stats.sensitivity = model.sensitivity_work().since(sensitivity);
        Ok(trajectory(track, I::METHOD, span, outcome))
    }
}

/// The trajectory a run recorded on `track` with `method`, and the failure that stopped it;
/// generic over the model only, like the track.
fn trajectory<N: Model>(
    mut track: Track<'_, '_, N>,
    method: Method,
    span: Span,
    outcome: Result<()>,
) -> (Trajectory<N::State>, Option<Error>) {
    let failure = outcome.err().map(|error| track.explain(error));
    let trajectory = Trajectory {
        model: N::NAME,
        method,
        stepping: match span {
            Span::Fixed { dt, .. } => Stepping::Fixed(dt),
            Span::Adaptive { tolerances, .. } => Stepping::Adaptive(tolerances),
        },
        stats: track.stats,
        samples: track.record.samples,
        events: track.record.events,
        dense: track.record.dense,
    };
    (trajectory, failure)
}
