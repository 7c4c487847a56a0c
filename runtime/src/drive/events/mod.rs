//! Events: a condition g(t, state) that stops the run or changes the state where it crosses
//! zero, located on the dense output; and time events that land the run exactly on given times.

use crate::trajectory::EventRecord;
use std::fmt;
use std::sync::Arc;

mod search;
mod tally;
mod watch;

pub(crate) use watch::{Outcome, Watch};

use crate::{Error, Result};

/// Which zero crossings of an event's condition count.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Direction {
    /// g goes from negative to positive.
    Rising,
    /// g goes from positive to negative (a falling ball's height).
    Falling,
    /// Either way.
    #[default]
    Either,
}

/// A change applied to the state at an event: `change(t, &mut y)`.
pub type StateChange<'a, S> = Arc<dyn Fn(f64, &mut S) + Send + Sync + 'a>;

/// An event function g(t, y) whose sign changes mark the event.
type Condition<'a, S> = Arc<dyn Fn(f64, &S) -> f64 + Send + Sync + 'a>;

/// What happens at an event.
pub enum Action<'a, S> {
    /// The run ends at the event; its last sample is the state there.
    Stop,
    /// The event is recorded and the run goes on unchanged.
    Record,
    /// The state is changed (a bounce, an impulse) and the run goes on from the new state; the
    /// method restarts there, forgetting what it reused.
    Change(StateChange<'a, S>),
}

impl<S> Clone for Action<'_, S> {
    fn clone(&self) -> Self {
        match self {
            Action::Stop => Action::Stop,
            Action::Record => Action::Record,
            Action::Change(f) => Action::Change(Arc::clone(f)),
        }
    }
}

/// What triggers an event.
enum Trigger<'a, S> {
    /// A zero of g(t, y) crossed in `direction`.
    Crossing {
        condition: Condition<'a, S>,
        direction: Direction,
    },
    /// These times, increasing: steps are shortened to land on each exactly.
    Times(Vec<f64>),
}

impl<S> Clone for Trigger<'_, S> {
    fn clone(&self) -> Self {
        match self {
            Trigger::Crossing {
                condition,
                direction,
            } => Trigger::Crossing {
                condition: Arc::clone(condition),
                direction: *direction,
            },
            Trigger::Times(times) => Trigger::Times(times.clone()),
        }
    }
}

/// An event of a run on states of type `S` (a model's generated state type).
///
/// ```
/// # use odyn_runtime::Event;
/// # #[derive(Clone, PartialEq, Debug)] struct BallState { y: f64, v: f64 }
/// // A ball that bounces off the ground keeping 90 % of its speed:
/// let bounce = Event::crossing("ground", |_t, s: &BallState| s.y)
///     .falling()
///     .change(|_t, s: &mut BallState| s.v = -0.9 * s.v);
/// // Stop when the ball is back at rest at the top of a bounce:
/// let apex = Event::crossing("apex", |_t, s: &BallState| s.v).falling().stop();
/// # let _ = (bounce, apex);
/// ```
///
/// A crossing is found by a sign change of g between the ends of an accepted step, then located
/// by root finding on the step's dense output to within [`crate::RunOptions::event_tolerance`]
/// in t, so events work with every method (fixed-step ones through a cubic Hermite
/// interpolant). Several crossings within one step are handled in time order; two crossings of
/// the same condition within one step cancel and are not seen (shorten `dt_max` if that can
/// happen).
///
/// **Simultaneous events.** Crossings located within the event tolerance of each other are one
/// instant. Every event there fires: each is recorded at that instant, and their actions apply
/// in the order the events were added to the run — each change sees the state the previous one
/// left, and each record holds the state before and after its own action. The run stops there
/// if any of them stops it.
///
/// **After a change** the state starts on the surface g = 0 of each event that fired (to within
/// the tolerance, on either side). Such an event is latched: it does not fire again as the state
/// leaves the surface. A state that moves back to the side it came from (a bounce) re-arms it —
/// even when it returns within the same step, however short the hop — and one that moves on
/// through (a change that did not reverse the crossing) releases it.
///
/// **Zeno behaviour.** A ball bouncing with restitution e < 1 bounces infinitely often before a
/// finite time. When a change event fires again sooner than the tolerance resolves, or its hop
/// no longer reaches the surface it left, the run ends with [`Error::EventsAccumulate`] naming
/// the event, its count and the time, rather than pass through the surface. A run also ends with
/// that error past [`crate::RunOptions::max_events`] events (default 100 000).
pub struct Event<'a, S> {
    name: String,
    trigger: Trigger<'a, S>,
    action: Action<'a, S>,
}

impl<S> Clone for Event<'_, S> {
    fn clone(&self) -> Self {
        Event {
            name: self.name.clone(),
            trigger: self.trigger.clone(),
            action: self.action.clone(),
        }
    }
}

impl<S> fmt::Debug for Event<'_, S> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let trigger = match &self.trigger {
            Trigger::Crossing { direction, .. } => format!("crossing ({direction:?})"),
            Trigger::Times(t) => format!("times {t:?}"),
        };
        let action = match self.action {
            Action::Stop => "stop",
            Action::Record => "record",
            Action::Change(_) => "change",
        };
        write!(f, "Event({:?}, {trigger}, {action})", self.name)
    }
}

impl<'a, S> Event<'a, S> {
    /// An event at the zeros of `condition`(t, state), in either direction, that stops the run.
    pub fn crossing(
        name: impl Into<String>,
        condition: impl Fn(f64, &S) -> f64 + Send + Sync + 'a,
    ) -> Self {
        Event {
            name: name.into(),
            trigger: Trigger::Crossing {
                condition: Arc::new(condition),
                direction: Direction::Either,
            },
            action: Action::Stop,
        }
    }

    /// An event at each of `times`: steps are shortened to land on them exactly, and the state
    /// there is recorded (the default action) — or the run stops or the state changes there.
    pub fn at_times(name: impl Into<String>, times: impl Into<Vec<f64>>) -> Self {
        Event {
            name: name.into(),
            trigger: Trigger::Times(times.into()),
            action: Action::Record,
        }
    }

    /// Counts only crossings in `direction` (crossing events; ignored for time events).
    pub fn direction(mut self, direction: Direction) -> Self {
        if let Trigger::Crossing { direction: d, .. } = &mut self.trigger {
            *d = direction;
        }
        self
    }

    /// Counts only crossings from negative to positive.
    pub fn rising(self) -> Self {
        self.direction(Direction::Rising)
    }

    /// Counts only crossings from positive to negative.
    pub fn falling(self) -> Self {
        self.direction(Direction::Falling)
    }

    /// Stops the run at the event.
    pub fn stop(mut self) -> Self {
        self.action = Action::Stop;
        self
    }

    /// Records the event and goes on.
    pub fn record(mut self) -> Self {
        self.action = Action::Record;
        self
    }

    /// Changes the state at the event with `change`(t, state) and goes on.
    pub fn change(mut self, change: impl Fn(f64, &mut S) + Send + Sync + 'a) -> Self {
        self.action = Action::Change(Arc::new(change));
        self
    }

    /// The event's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Checks the event for a run from `t0`.
    ///
    /// Errors: [`Error::InvalidInput`] for time events whose times are not finite or not
    /// increasing.
    pub(crate) fn check(&self) -> Result<()> {
        if let Trigger::Times(times) = &self.trigger {
            if let Some(t) = times.iter().find(|t| !t.is_finite()) {
                return Err(Error::invalid(
                    format!("event `{}`", self.name),
                    format!("its times must be finite, got {t:?}"),
                ));
            }
            if times.windows(2).any(|w| w[1] <= w[0]) {
                return Err(Error::invalid(
                    format!("event `{}`", self.name),
                    "its times must be strictly increasing",
                ));
            }
        }
        Ok(())
    }
}

/// `g`, the value of `event`'s condition at `t`, if it is not NaN (infinities have a sign).
pub(super) fn finite_condition<S>(event: &Event<'_, S>, t: f64, g: f64) -> Result<f64> {
    if g.is_nan() {
        return Err(nan_condition(event, t));
    }
    Ok(g)
}

/// The error for `event`'s condition returning NaN at `t`.
pub(super) fn nan_condition<S>(event: &Event<'_, S>, t: f64) -> Error {
    Error::BadEvent {
        event: event.name.clone(),
        t,
        reason: "its condition returned NaN, which has no sign, so a crossing there would be \
                 missed; a condition must be a number wherever the run goes"
            .to_owned(),
    }
}
