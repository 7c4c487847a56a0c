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

/// An event whose condition sits on zero at the start of a step: the sign it has there is no
/// guide to the next crossing.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Latch {
    /// Not on zero: the next crossing is a sign change from g at the start of the step.
    Off,
    /// On zero with no side known (a run or a change from outside that starts there): the side
    /// is read a little into the step.
    Unknown,
    /// The event fired at a change and the state goes on from its surface, where g is zero to
    /// within the location tolerance (on either side of it by rounding). `side` is the sign g
    /// had before the crossing: a state that moves back to that side (a bounce) re-arms the
    /// event there, one that moves on (a change that did not reverse the crossing) releases it.
    Fired { side: f64 },
}

/// A crossing located in the step being handled.
#[derive(Clone, Copy, Debug)]
struct Found {
    t: f64,
    event: usize,
    /// The sign of g before the crossing (0 for time events).
    side: f64,
}

/// The events of a run and what they remember between steps.
pub(crate) struct Watch<'a, S> {
    events: Vec<Event<'a, S>>,
    /// g at the start of the current step, per event (unused for time events).
    g: Vec<f64>,
    /// g at the end of the current step.
    g_end: Vec<f64>,
    /// Per event, whether g sits on zero at the start of the step.
    latch: Vec<Latch>,
    /// Per time event, the index of its next time.
    next_time: Vec<usize>,
    /// Per event, how often it fired and when it last changed the state.
    fired: Vec<(u64, f64)>,
    /// Events recorded so far in the run, against `max_events`.
    total: u64,
    max_events: u64,
    /// Tolerance in t for locating crossings.
    tolerance: f64,
    /// The crossings of the step being handled (kept to reuse its allocation).
    found: Vec<Found>,
}

impl<'a, S: State> Watch<'a, S> {
    /// The events of a run from (t₀, y₀), every condition evaluated there.
    ///
    /// Errors: [`Error::BadEvent`] when a condition is NaN at (t₀, y₀).
    pub(crate) fn new(
        events: Vec<Event<'a, S>>,
        t0: f64,
        y0: &S,
        tolerance: f64,
        max_events: u64,
    ) -> Result<Self> {
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
            latch: vec![Latch::Off; n],
            fired: vec![(0, f64::NEG_INFINITY); n],
            total: 0,
            max_events,
            tolerance,
            found: Vec::new(),
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
                self.latch[i] = if self.g[i] == 0.0 {
                    Latch::Unknown
                } else {
                    Latch::Off
                };
            }
        }
        Ok(())
    }

    /// Whether an event is latched on a surface it fired at: handling the next step then needs
    /// f at its start, the direction the state leaves the surface in.
    pub(crate) fn latched(&self) -> bool {
        self.latch.iter().any(|l| matches!(l, Latch::Fired { .. }))
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
                    any |= self.latch[i] != Latch::Off || crosses(self.g[i], g1, *direction);
                }
                Trigger::Times(times) => {
                    any |= times.get(self.next_time[i]).is_some_and(|&s| s <= t1);
                }
            }
        }
        Ok(any)
    }

    /// Handles the events of the accepted step `dense` (from t to t1 = t + h, ending at `y1`),
    /// after [`Watch::scan`] found something (`f0` is f at the start when [`Watch::latched`]): locates each crossing, then takes them in time
    /// order, instant by instant. Crossings within the location tolerance of each other are one
    /// instant: every event there is recorded on the state at that instant, and their actions
    /// apply in the order of the run's event list (each change sees the state the previous one
    /// left); a change or a stop among them ends the step there. On return `at` holds the state
    /// at the returned time (after the actions), or `y1` when the step went through.
    ///
    /// Errors: [`Error::BadEvent`] when a condition is NaN where a crossing is sought, or a change
    /// leaves the state non-finite or its condition NaN; [`Error::EventsAccumulate`] when a
    /// change event fires again sooner than the tolerance resolves, or the run's events exceed
    /// its `max_events`.
    pub(crate) fn handle(
        &mut self,
        dense: &DenseStep<S>,
        t1: f64,
        y1: &S,
        f0: &S,
        at: &mut S,
        records: &mut Vec<EventRecord<S>>,
    ) -> Result<Outcome> {
        let mut found = std::mem::take(&mut self.found);
        found.clear();
        let located = self.locate_all(dense, t1, f0, at, &mut found);
        let outcome = located.and_then(|()| self.act(&found, dense, t1, y1, at, records));
        self.found = found;
        let outcome = outcome?;
        if let Outcome::Continue = outcome {
            at.clone_from(y1);
            self.advance();
        }
        Ok(outcome)
    }

    /// Locates every event's first crossing in the step (and its times inside it), into `found`
    /// sorted by time, then by position in the event list.
    fn locate_all(
        &mut self,
        dense: &DenseStep<S>,
        t1: f64,
        f0: &S,
        at: &mut S,
        found: &mut Vec<Found>,
    ) -> Result<()> {
        for i in 0..self.events.len() {
            let e = &self.events[i];
            match &e.trigger {
                Trigger::Crossing {
                    condition,
                    direction,
                } => {
                    // Whether a latched event's state leaves the surface back towards the side
                    // it came from, along the tangent: a hop shorter than the search for its top
                    // resolves still shows in that.
                    let back = if let Latch::Fired { side } = self.latch[i] {
                        let dt = 1e-6 * dense.h;
                        let y0 = dense.coefficients()[0].as_slice();
                        for ((a, y), f) in at.as_mut_slice().iter_mut().zip(y0).zip(f0.as_slice()) {
                            *a = y + dt * f;
                        }
                        side * (condition(dense.t + dt, at) - self.g[i]) > 0.0
                    } else {
                        false
                    };
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
                    let end = (t1, self.g_end[i]);
                    let mut latch = self.latch[i];
                    let start = match latch {
                        Latch::Off => Some((dense.t, self.g[i])),
                        Latch::Unknown => {
                            // g on zero at the start (a run or a state from outside starting
                            // there) has no sign: read it a little into the step.
                            let delta = (10.0 * self.tolerance)
                                .max(1e-9 * (t1 - dense.t))
                                .min(0.01 * (t1 - dense.t));
                            Some((dense.t + delta, g(dense.t + delta)))
                        }
                        Latch::Fired { side } => {
                            let start = (dense.t, self.g[i]);
                            match rearm(&mut g, side, back, start, end, self.tolerance) {
                                Rearm::Armed(point) => {
                                    latch = Latch::Off;
                                    Some(point)
                                }
                                Rearm::Held => None,
                                Rearm::Released => {
                                    latch = Latch::Off;
                                    None
                                }
                                Rearm::Unresolved(t) => {
                                    return Err(self.accumulating(i, t));
                                }
                            }
                        }
                    };
                    if let Some(start) = start
                        && crosses(start.1, end.1, *direction)
                    {
                        let t = locate(&mut g, start, end, self.tolerance);
                        found.push(Found {
                            t,
                            event: i,
                            side: start.1.signum(),
                        });
                    }
                    if let Some(t) = nan_at {
                        return Err(nan_condition(e, t));
                    }
                    self.latch[i] = latch;
                }
                Trigger::Times(times) => {
                    let mut k = self.next_time[i];
                    while let Some(&s) = times.get(k).filter(|&&s| s <= t1) {
                        found.push(Found {
                            t: s,
                            event: i,
                            side: 0.0,
                        });
                        k += 1;
                    }
                }
            }
        }
        found.sort_unstable_by(|a, b| a.t.total_cmp(&b.t).then(a.event.cmp(&b.event)));
        Ok(())
    }

    /// Takes the located events instant by instant (see [`Watch::handle`]).
    fn act(
        &mut self,
        found: &[Found],
        dense: &DenseStep<S>,
        t1: f64,
        y1: &S,
        at: &mut S,
        records: &mut Vec<EventRecord<S>>,
    ) -> Result<Outcome> {
        let mut rest = found;
        while let Some(first) = rest.first() {
            let window = self.tolerance.max(4.0 * ulp(first.t));
            let count = rest.partition_point(|f| f.t <= first.t + window);
            let (instant, later) = rest.split_at(count);
            rest = later;
            // The latest crossing of the instant: past every one of them.
            let t = instant.iter().fold(first.t, |m, f| m.max(f.t));
            if t == t1 {
                at.clone_from(y1);
            } else {
                dense.eval((t - dense.t) / dense.h, at);
            }
            let (mut changed, mut stop) = (false, false);
            for event in (0..self.events.len()).filter(|&i| instant.iter().any(|f| f.event == i)) {
                // A time event may list several times within the window.
                let times = instant.iter().filter(|f| f.event == event).count();
                if let Trigger::Times(_) = self.events[event].trigger {
                    self.next_time[event] += times;
                }
                let before = at.clone();
                match &self.events[event].action {
                    Action::Record => {}
                    Action::Stop => stop = true,
                    Action::Change(change) => {
                        change(t, at);
                        self.check_change(event, t, at)?;
                        changed = true;
                    }
                }
                self.count(event, t)?;
                records.push(EventRecord {
                    t,
                    event,
                    name: self.events[event].name.clone(),
                    before,
                    after: at.clone(),
                });
            }
            if changed {
                self.reset(t, at)?;
                // The events of the instant left their conditions on (or a rounding away from)
                // zero: each is latched on the side it came from.
                for f in instant.iter().filter(|f| f.side != 0.0) {
                    self.latch[f.event] = Latch::Fired { side: f.side };
                }
            }
            if stop {
                return Ok(Outcome::Stop(t));
            }
            if changed {
                return Ok(Outcome::Changed(t));
            }
        }
        Ok(Outcome::Continue)
    }

    /// Counts a firing of `event` at `t` against the run's budget and, for a change, against
    /// the last change: a change that comes back sooner than the tolerance resolves is an
    /// accumulation of events.
    fn count(&mut self, event: usize, t: f64) -> Result<()> {
        self.total += 1;
        let (count, last) = &mut self.fired[event];
        *count += 1;
        let window = self.tolerance.max(4.0 * ulp(t));
        if let Action::Change(_) = self.events[event].action {
            if t - *last <= window {
                return Err(self.accumulating(event, t));
            }
            *last = t;
        }
        if self.total > self.max_events {
            let (count, _) = self.fired[event];
            return Err(Error::EventsAccumulate {
                event: self.events[event].name.clone(),
                count,
                t,
                reason: format!(
                    "the run's events passed `max_events` = {}; raise it if so many are expected, \
                     or stop the run sooner",
                    self.max_events
                ),
            });
        }
        Ok(())
    }

    /// The error for `event`'s changes accumulating at `t`.
    fn accumulating(&self, event: usize, t: f64) -> Error {
        Error::EventsAccumulate {
            event: self.events[event].name.clone(),
            count: self.fired[event].0,
            t,
            reason: format!(
                "after its last change the state comes back to its surface sooner than the event \
                 tolerance ({:e}) resolves: its events accumulate at this time (Zeno behaviour, \
                 like a ball bouncing ever lower) and integrating on would pass through the \
                 surface; end the run before, e.g. with a stop event when the bounce speed falls \
                 below a threshold",
                self.tolerance
            ),
        }
    }

    /// Checks the state a change left.
    fn check_change(&self, event: usize, t: f64, at: &S) -> Result<()> {
        match at.as_slice().iter().position(|x| !x.is_finite()) {
            None => Ok(()),
            Some(k) => Err(Error::BadEvent {
                event: self.events[event].name.clone(),
                t,
                reason: format!(
                    "its change left component `{}` = {:?}; the state after a change must be \
                     finite",
                    at.component_name(k),
                    at.as_slice()[k]
                ),
            }),
        }
    }

    /// The step went through: the end values are the next step's start values. An event that
    /// fired at a change stays latched while g has not left its surface for either side.
    pub(crate) fn advance(&mut self) {
        std::mem::swap(&mut self.g, &mut self.g_end);
        for (latch, g) in self.latch.iter_mut().zip(&self.g) {
            *latch = match *latch {
                // Held: `rearm` releases or re-arms it once g leaves the surface.
                Latch::Fired { .. } => *latch,
                _ if *g == 0.0 => Latch::Unknown,
                _ => Latch::Off,
            };
        }
    }
}

/// Where a latched event stands after a step.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Rearm {
    /// g reached the side it came from at this point (t, g): a crossing after it counts.
    Armed((f64, f64)),
    /// g is still on its way back to the surface: no crossing in this step.
    Held,
    /// g moved away from the surface on the far side: the change did not reverse the crossing.
    Released,
    /// g turned back towards the surface and away again without reaching it, at this time: a
    /// return sooner than the tolerance resolves.
    Unresolved(f64),
}

/// Where the event latched on the `side` it came from stands after the step from `start` to
/// `end` (each (t, g)): the highest point of side·g on the step, by golden-section search to
/// within `tolerance` in t (Kiefer, Proc. AMS 4 (1953) 502), says whether the state came back;
/// `back` says whether it leaves the surface towards that side, for a hop too short to find.
fn rearm(
    mut g: impl FnMut(f64) -> f64,
    side: f64,
    back: bool,
    start: (f64, f64),
    end: (f64, f64),
    tolerance: f64,
) -> Rearm {
    let phi = |g: f64| side * g;
    let (a, b) = (start.0, end.0);
    let mut best = if phi(end.1) >= phi(start.1) {
        end
    } else {
        start
    };
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let (mut lo, mut hi) = (a, b);
    let mut x1 = hi - ratio * (hi - lo);
    let mut x2 = lo + ratio * (hi - lo);
    let (mut f1, mut f2) = (g(x1), g(x2));
    for _ in 0..200 {
        for (x, f) in [(x1, f1), (x2, f2)] {
            if phi(f) > phi(best.1) {
                best = (x, f);
            }
        }
        if phi(best.1) > 0.0 || hi - lo <= tolerance.max(4.0 * ulp(hi)) {
            break;
        }
        if phi(f1) >= phi(f2) {
            (hi, x2, f2) = (x2, x1, f1);
            x1 = hi - ratio * (hi - lo);
            f1 = g(x1);
        } else {
            (lo, x1, f1) = (x1, x2, f2);
            x2 = lo + ratio * (hi - lo);
            f2 = g(x2);
        }
    }
    if phi(best.1) > 0.0 {
        Rearm::Armed(best)
    } else if best.0 == b {
        Rearm::Held
    } else if best.0 == a && !back {
        Rearm::Released
    } else {
        Rearm::Unresolved(best.0)
    }
}

/// The spacing of floats at `t`.
fn ulp(t: f64) -> f64 {
    let t = t.abs();
    if t == 0.0 {
        f64::MIN_POSITIVE
    } else {
        f64::from_bits(t.to_bits() + 1) - t
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
