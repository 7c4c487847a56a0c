//! Events: a condition g(t, state) that stops the run or changes the state where it crosses
//! zero, located on the dense output; and time events that land the run exactly on given times.

use std::fmt;
use std::sync::Arc;

use super::DenseStep;
use crate::{Error, Result, State};

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
/// happen). After a [`Action::Change`], a crossing of that event within the time tolerance of the
/// change is ignored, so a reset state sitting on g = 0 does not trigger again.
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

/// One event that happened, as a trajectory records it.
#[derive(Clone, Debug, PartialEq)]
pub struct EventRecord<S> {
    /// When.
    pub t: f64,
    /// Which event: its index in the run's event list.
    pub event: usize,
    /// Its name.
    pub name: String,
    /// The state at the event, before its action.
    pub before: S,
    /// The state after its action (equal to `before` unless the action changed it).
    pub after: S,
}

/// What an event did to the run.
pub(crate) enum Outcome {
    /// Nothing that cuts the step short (none happened, or only recorded ones).
    Continue,
    /// The run stops at this time.
    Stop(f64),
    /// The state was changed at this time; the method restarts there.
    Changed(f64),
}

/// The events of a run and what they remember between steps.
pub(crate) struct Watch<'a, S> {
    events: Vec<Event<'a, S>>,
    /// g at the start of the current step, per event (unused for time events).
    g: Vec<f64>,
    /// g at the end of the current step.
    g_end: Vec<f64>,
    /// The time of each event's last change, so it does not re-trigger on the reset state.
    changed_at: Vec<f64>,
    /// Per event, whether g sits on zero at the start of the step (just reset there, or started
    /// there): its sign is then read a little into the step, on the dense output.
    ahead: Vec<bool>,
    /// Per time event, the index of its next time.
    next_time: Vec<usize>,
    /// Tolerance in t for locating crossings.
    tolerance: f64,
}

impl<'a, S: State> Watch<'a, S> {
    /// The events of a run from (t₀, y₀), every condition evaluated there.
    ///
    /// Errors: [`Error::BadEvent`] when a condition is NaN at (t₀, y₀).
    pub(crate) fn new(events: Vec<Event<'a, S>>, t0: f64, y0: &S, tolerance: f64) -> Result<Self> {
        let n = events.len();
        let mut watch = Watch {
            next_time: events
                .iter()
                .map(|e| match &e.trigger {
                    Trigger::Times(times) => times.partition_point(|&t| t <= t0),
                    Trigger::Crossing { .. } => 0,
                })
                .collect(),
            events,
            g: vec![0.0; n],
            g_end: vec![0.0; n],
            changed_at: vec![f64::NEG_INFINITY; n],
            ahead: vec![false; n],
            tolerance,
        };
        watch.reset(t0, y0)?;
        Ok(watch)
    }

    pub(crate) fn is_empty(&self) -> bool {
        self.events.is_empty()
    }

    /// The state was changed from outside at t: the conditions start afresh there.
    pub(crate) fn restart(&mut self, t: f64, y: &S) -> Result<()> {
        self.reset(t, y)
    }

    /// Re-evaluates every condition at (t, y): at the start, and after the state changed.
    fn reset(&mut self, t: f64, y: &S) -> Result<()> {
        for (i, e) in self.events.iter().enumerate() {
            if let Trigger::Crossing { condition, .. } = &e.trigger {
                self.g[i] = finite_condition(e, t, condition(t, y))?;
                self.ahead[i] = self.g[i] == 0.0;
            }
        }
        Ok(())
    }

    /// The next time a time event needs a step to land on, after `t`.
    pub(crate) fn next_stop(&self) -> f64 {
        self.events
            .iter()
            .zip(&self.next_time)
            .filter_map(|(e, &i)| match &e.trigger {
                Trigger::Times(times) => times.get(i).copied(),
                Trigger::Crossing { .. } => None,
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Whether a crossing may have happened in the step ending at (t1, y1): evaluates every
    /// condition there. Cheap; the caller builds the dense output only when this says so.
    ///
    /// Errors: [`Error::BadEvent`] when a condition is NaN there.
    pub(crate) fn scan(&mut self, t1: f64, y1: &S) -> Result<bool> {
        let mut any = false;
        for (i, e) in self.events.iter().enumerate() {
            match &e.trigger {
                Trigger::Crossing {
                    condition,
                    direction,
                } => {
                    let g1 = finite_condition(e, t1, condition(t1, y1))?;
                    self.g_end[i] = g1;
                    any |= self.ahead[i] || crosses(self.g[i], g1, *direction);
                }
                Trigger::Times(times) => {
                    any |= times.get(self.next_time[i]).is_some_and(|&s| s <= t1);
                }
            }
        }
        Ok(any)
    }

    /// Handles the events of the accepted step `dense` (from t to t1 = t + h, ending at `y1`),
    /// after [`Watch::scan`] found something: locates each crossing, then takes them in time
    /// order — recording, and stopping or changing the state at the first that does. On return
    /// `at` holds the state at the returned time (the event's, after its action), or `y1` when
    /// the step went through.
    ///
    /// Errors: [`Error::BadEvent`] when a condition is NaN where a crossing is sought, or a change
    /// leaves the state non-finite or its condition NaN.
    pub(crate) fn handle(
        &mut self,
        dense: &DenseStep<S>,
        t1: f64,
        y1: &S,
        at: &mut S,
        records: &mut Vec<EventRecord<S>>,
    ) -> Result<Outcome> {
        let mut found: Vec<(f64, usize)> = Vec::new();
        for (i, e) in self.events.iter().enumerate() {
            match &e.trigger {
                Trigger::Crossing {
                    condition,
                    direction,
                } => {
                    // The first time inside the step where the condition was NaN, if any.
                    let mut nan_at = None;
                    let mut g = |t: f64| {
                        dense.eval((t - dense.t) / dense.h, at);
                        let value = condition(t, at);
                        if value.is_nan() {
                            nan_at.get_or_insert(t);
                        }
                        value
                    };
                    // g on zero at the start (a state just reset onto it) has no sign: read it
                    // a little into the step, past the tolerance the event was located to.
                    let start = if self.ahead[i] {
                        let delta = (10.0 * self.tolerance)
                            .max(1e-9 * (t1 - dense.t))
                            .min(0.01 * (t1 - dense.t));
                        (dense.t + delta, g(dense.t + delta))
                    } else {
                        (dense.t, self.g[i])
                    };
                    if crosses(start.1, self.g_end[i], *direction) {
                        let t = locate(&mut g, start, (t1, self.g_end[i]), self.tolerance);
                        if t > self.changed_at[i] + self.tolerance {
                            found.push((t, i));
                        }
                    }
                    if let Some(t) = nan_at {
                        return Err(nan_condition(e, t));
                    }
                }
                Trigger::Times(times) => {
                    let mut k = self.next_time[i];
                    while let Some(&s) = times.get(k).filter(|&&s| s <= t1) {
                        found.push((s, i));
                        k += 1;
                    }
                }
            }
        }
        found.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        for (t, i) in found {
            if let Trigger::Times(_) = self.events[i].trigger {
                self.next_time[i] += 1;
            }
            if t == t1 {
                at.clone_from(y1);
            } else {
                dense.eval((t - dense.t) / dense.h, at);
            }
            let before = at.clone();
            let event = &self.events[i];
            let outcome = match &event.action {
                Action::Record => Outcome::Continue,
                Action::Stop => Outcome::Stop(t),
                Action::Change(change) => {
                    change(t, at);
                    if let Some(k) = at.as_slice().iter().position(|x| !x.is_finite()) {
                        return Err(Error::BadEvent {
                            event: event.name.clone(),
                            t,
                            reason: format!(
                                "its change left component `{}` = {:?}; the state after a \
                                 change must be finite",
                                at.component_name(k),
                                at.as_slice()[k]
                            ),
                        });
                    }
                    Outcome::Changed(t)
                }
            };
            records.push(EventRecord {
                t,
                event: i,
                name: event.name.clone(),
                before,
                after: at.clone(),
            });
            match outcome {
                Outcome::Continue => {}
                Outcome::Changed(t) => {
                    self.changed_at[i] = t;
                    self.reset(t, at)?;
                    // The event left its condition at (or a rounding away from) zero.
                    self.ahead[i] = true;
                    return Ok(outcome);
                }
                Outcome::Stop(_) => return Ok(outcome),
            }
        }
        at.clone_from(y1);
        self.advance();
        Ok(Outcome::Continue)
    }

    /// The step went through: the end values are the next step's start values.
    pub(crate) fn advance(&mut self) {
        std::mem::swap(&mut self.g, &mut self.g_end);
        for (ahead, g) in self.ahead.iter_mut().zip(&self.g) {
            *ahead = *g == 0.0;
        }
    }
}

/// `g`, the value of `event`'s condition at `t`, if it is not NaN (infinities have a sign).
fn finite_condition<S>(event: &Event<'_, S>, t: f64, g: f64) -> Result<f64> {
    if g.is_nan() {
        return Err(nan_condition(event, t));
    }
    Ok(g)
}

/// The error for `event`'s condition returning NaN at `t`.
fn nan_condition<S>(event: &Event<'_, S>, t: f64) -> Error {
    Error::BadEvent {
        event: event.name.clone(),
        t,
        reason: "its condition returned NaN, which has no sign, so a crossing there would be \
                 missed; a condition must be a number wherever the run goes"
            .to_owned(),
    }
}

/// Whether g going from `g0` to `g1` crosses zero in `direction`. A g that reaches zero exactly
/// at the end counts; one that leaves zero at the start does not (it crossed in the last step).
fn crosses(g0: f64, g1: f64, direction: Direction) -> bool {
    let rising = g0 < 0.0 && g1 >= 0.0;
    let falling = g0 > 0.0 && g1 <= 0.0;
    match direction {
        Direction::Rising => rising,
        Direction::Falling => falling,
        Direction::Either => rising || falling,
    }
}

/// The zero of g in [a, b], where g(a) and g(b) have opposite signs (or g(b) = 0), to within
/// `tolerance` in t: the Illinois variant of regula falsi (Dowell & Jarratt, BIT 11 (1971)
/// 168), superlinear, with bisection steps if it stalls. Returns the end of the final bracket
/// on the far side of the root, so the located event never precedes the crossing.
fn locate(
    mut g: impl FnMut(f64) -> f64,
    (mut a, mut ga): (f64, f64),
    (mut b, mut gb): (f64, f64),
    tolerance: f64,
) -> f64 {
    if gb == 0.0 {
        return b;
    }
    let mut side = 0i8;
    for iteration in 0..200 {
        if (b - a).abs() <= tolerance {
            break;
        }
        // Every third step bisects: Illinois alone can crawl on a flat g, and 66 halvings in
        // the 200 iterations reach any tolerance.
        let mut t = if iteration % 3 == 2 {
            0.5 * (a + b)
        } else {
            (a * gb - b * ga) / (gb - ga)
        };
        if !(t > a.min(b) && t < a.max(b)) {
            t = 0.5 * (a + b);
            if t == a || t == b {
                // Adjacent floats: the bracket cannot shrink further.
                break;
            }
        }
        let gt = g(t);
        if gt == 0.0 {
            return t;
        }
        if (gt > 0.0) == (gb > 0.0) {
            b = t;
            gb = gt;
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        } else {
            a = t;
            ga = gt;
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        }
    }
    b
}

#[cfg(test)]
mod tests {
    use super::{Direction, crosses, locate};

    #[test]
    fn crossings_respect_the_direction() {
        assert!(crosses(1.0, -1.0, Direction::Falling));
        assert!(!crosses(1.0, -1.0, Direction::Rising));
        assert!(crosses(-1.0, 0.0, Direction::Rising));
        assert!(!crosses(0.0, 1.0, Direction::Either));
        assert!(crosses(1.0, -1.0, Direction::Either));
    }

    #[test]
    fn roots_are_located_to_the_tolerance() {
        // cos t on [1, 2]: root π/2.
        let t = locate(f64::cos, (1.0, 1f64.cos()), (2.0, 2f64.cos()), 1e-14);
        assert!((t - std::f64::consts::FRAC_PI_2).abs() < 2e-14, "{t}");
        assert!(t >= std::f64::consts::FRAC_PI_2);
        // A very flat function still converges (bisection fallback).
        let g = |t: f64| (t - 0.3).powi(9);
        let t = locate(g, (0.0, g(0.0)), (1.0, g(1.0)), 1e-12);
        assert!((t - 0.3).abs() < 1e-11, "{t}");
    }
}
