//! [`RunOptions`] and [`Length`]: what a run is asked for, the defaults, and the one check of
//! them against the run's initial state.

use crate::checks::{check_dt, check_t0, divergence_limit};
use crate::drive::AdaptiveOptions;
use crate::{Error, Method, NewtonOptions, Result, Stepping, Tolerances};

/// How long a run lasts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Length {
    /// Exactly this many steps (fixed-step runs only).
    Steps(u64),
    /// Simulated seconds. An adaptive run ends exactly at t₀ + duration; a fixed-step run takes
    /// ⌈duration/dt⌉ steps (a ratio within 1e-9 of a whole number counts as that number), so it
    /// ends at or just past it.
    Duration(f64),
}

/// Everything a run needs besides the model, its initial state and its events.
#[derive(Clone, Debug, PartialEq)]
pub struct RunOptions {
    /// The integrator. Default: the model's `#[system(integrator = ...)]`, else [`Method::Rk4`].
    pub integrator: Method,
    /// Fixed dt or tolerances. Default: the attribute's `rtol`/`atol`, else its `dt`; with
    /// neither, adaptive methods use the default [`Tolerances`] and fixed-step methods need a
    /// `.dt(..)`.
    pub stepping: Option<Stepping>,
    /// How long to run. Default: none; a run without one is an error.
    pub length: Option<Length>,
    /// Start time (default 0).
    pub t0: f64,
    /// Record every n-th step (default 1: every grid step, or every accepted step of an adaptive
    /// run); the initial and final states are always recorded.
    pub record_every: u64,
    /// Record only at these times (strictly increasing), evaluated on the dense output, besides
    /// the initial and final states; times outside the run are skipped. Default: none.
    pub save_at: Option<Vec<f64>>,
    /// Keep every step's dense-output polynomial so [`Trajectory::at`](crate::Trajectory::at)
    /// works anywhere. Default: on for adaptive runs that record every step, off for fixed-step
    /// ones (where it costs one more evaluation of f a step for the Hermite interpolant) and for
    /// runs that limit their recording with `save_at` or `record_every` — the polynomials hold
    /// (order + 1) states a step, which for a big field model is the run's memory (1.1 GB for
    /// BDF on a 128² Brusselator) and a fifth of its time.
    pub dense_output: Option<bool>,
    /// |component| beyond which a step counts as diverged. Default: 10¹⁰ × max(1, largest
    /// |component| of the initial state) — far beyond anything an accurate run of a bounded model
    /// reaches, and where an exploded explicit run of a stiff model is caught before its values
    /// overflow. A non-finite state always stops the run, whatever the limit (`f64::INFINITY`
    /// catches only infinities and NaN).
    pub divergence_limit: Option<f64>,
    /// Newton's method in implicit steps (see [`NewtonOptions`] for the defaults).
    pub newton: NewtonOptions,
    /// First step, step bounds, step budget and controller of adaptive runs (see
    /// [`AdaptiveOptions`] for the defaults).
    pub adaptive: AdaptiveOptions,
    /// Events are located to within this time (default 1e-12, or the resolution of t if
    /// coarser). Crossings within it of each other are one instant (see [`Event`](crate::Event)).
    pub event_tolerance: f64,
    /// The most events one run records (default 100 000): past it the run ends with
    /// [`Error::EventsAccumulate`] rather than fill memory with an event that fires without end.
    pub max_events: u64,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            integrator: Method::Rk4,
            stepping: None,
            length: None,
            t0: 0.0,
            record_every: 1,
            save_at: None,
            dense_output: None,
            divergence_limit: None,
            newton: NewtonOptions::default(),
            adaptive: AdaptiveOptions::default(),
            event_tolerance: 1e-12,
            max_events: 100_000,
        }
    }
}

/// The options of a run, checked against its initial state.
pub(super) struct Checked {
    /// How it steps and where it ends.
    pub(super) span: Span,
    /// The divergence limit, the default resolved.
    pub(super) limit: f64,
    /// Whether it keeps every step's dense output.
    pub(super) dense: bool,
}

/// How a validated run steps and where it ends.
#[derive(Clone, Debug)]
pub(super) enum Span {
    /// `steps` steps of `dt`.
    Fixed { dt: f64, steps: u64 },
    /// To `t_end`, each step within `tolerances`.
    Adaptive { tolerances: Tolerances, t_end: f64 },
}

impl RunOptions {
    /// Checks every option for a run with `method` stepping by `stepping` (the options' own,
    /// unless a typed run changed the method) from `initial`: the one place each is validated.
    /// `unsupported` makes the error for a method that cannot do what the options ask.
    // Not generic (the state as a slice, the error maker as an object): one copy for every
    // model a program runs.
    pub(super) fn check(
        &self,
        method: Method,
        stepping: Option<&Stepping>,
        initial: &[f64],
        unsupported: &dyn Fn(&'static str) -> Error,
    ) -> Result<Checked> {
        let o = self;
        let stepping = match (stepping, method.is_adaptive()) {
            (Some(Stepping::Fixed(dt)), _) => {
                check_dt(*dt)?;
                Stepping::Fixed(*dt)
            }
            (Some(Stepping::Adaptive(tolerances)), true) => {
                tolerances.check(initial.len())?;
                Stepping::Adaptive(tolerances.clone())
            }
            (Some(Stepping::Adaptive(_)), false) => {
                return Err(unsupported(
                    "it has no error estimate, so it cannot step to tolerances; give it a \
                     `.dt(..)`, or choose an adaptive method (Tsit5, Dop853)",
                ));
            }
            (None, true) => Stepping::Adaptive(Tolerances::default()),
            (None, false) => {
                return Err(Error::invalid(
                    "dt",
                    "no step given: call `.dt(..)` or set `#[system(dt = ..)]`",
                ));
            }
        };
        let length = o.length.ok_or_else(|| {
            Error::invalid(
                "length",
                "no run length given: call `.steps(..)` or `.duration(..)`",
            )
        })?;
        check_t0(o.t0)?;
        let dense = o.dense_output.unwrap_or(
            matches!(stepping, Stepping::Adaptive(_)) && o.save_at.is_none() && o.record_every == 1,
        );
        let span = match (stepping, length) {
            (Stepping::Fixed(dt), Length::Steps(steps)) => Span::Fixed { dt, steps },
            (Stepping::Fixed(dt), Length::Duration(d)) => Span::Fixed {
                dt,
                steps: steps_for(d, dt)?,
            },
            (Stepping::Adaptive(tolerances), Length::Duration(d)) => {
                let t_end = o.t0 + checked_duration(d)?;
                if d > 0.0 && t_end == o.t0 {
                    return Err(Error::invalid(
                        "duration",
                        format!(
                            "{d:e} is below the resolution of t at the start time {:e}: the \
                             run would not move; use a start time nearer 0",
                            o.t0
                        ),
                    ));
                }
                Span::Adaptive { tolerances, t_end }
            }
            (Stepping::Adaptive(_), Length::Steps(_)) => {
                return Err(Error::invalid(
                    "length",
                    "an adaptive run chooses its own steps: give it a `.duration(..)`, or a \
                     `.dt(..)` to run a fixed number of fixed steps",
                ));
            }
        };
        if o.record_every == 0 {
            return Err(Error::invalid("record_every", "must be at least 1"));
        }
        if let Some(times) = &o.save_at {
            if let Some(t) = times.iter().find(|t| !t.is_finite()) {
                return Err(Error::invalid(
                    "save_at",
                    format!("times must be finite, got {t:?}"),
                ));
            }
            if times.windows(2).any(|w| w[1] <= w[0]) {
                return Err(Error::invalid(
                    "save_at",
                    "times must be strictly increasing",
                ));
            }
        }
        let limit = divergence_limit(o.divergence_limit, initial)?;
        if !(o.event_tolerance.is_finite() && o.event_tolerance >= 0.0) {
            return Err(Error::invalid(
                "event_tolerance",
                format!(
                    "must be finite and non-negative, got {:?}",
                    o.event_tolerance
                ),
            ));
        }
        o.adaptive.check()?;
        if let Span::Adaptive { t_end, .. } = &span
            && o.adaptive.dt_min > t_end - o.t0
        {
            return Err(Error::invalid(
                "dt_min",
                format!(
                    "{:e} is longer than the run ({:e}): no step could be taken; lower it",
                    o.adaptive.dt_min,
                    t_end - o.t0
                ),
            ));
        }
        // `newton` is checked by `Integrator::start`, where every run, stepper and hand-driven
        // integrator begins.
        Ok(Checked { span, limit, dense })
    }
}

fn checked_duration(duration: f64) -> Result<f64> {
    if duration.is_finite() && duration >= 0.0 {
        Ok(duration)
    } else {
        Err(Error::invalid(
            "duration",
            format!("must be finite and non-negative, got {duration:?}"),
        ))
    }
}

fn steps_for(duration: f64, dt: f64) -> Result<u64> {
    let duration = checked_duration(duration)?;
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
            format!(
                "{duration:?} s at dt = {dt:e} is {steps:e} steps, more than this runner takes"
            ),
        ));
    }
    Ok(steps as u64)
}
