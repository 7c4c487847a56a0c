//! The events of one run as the driver steps it: which crossings each accepted step holds, and
//! what happens at each instant.

mod instant;

use super::search::{Rearm, crosses, locate, rearm};
use super::tally::Tally;
use super::{Event, EventRecord, Trigger, finite_condition, nan_condition};
use crate::drive::DenseStep;
use crate::{Result, State};

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
    /// How often each event fired, against the run's budget and the accumulation of changes.
    tally: Tally,
    /// Tolerance in t for locating crossings.
    tolerance: f64,
    /// The crossings of the step being handled (kept to reuse its allocation).
    found: Vec<Found>,
}

impl<'a, S: State> Watch<'a, S> {
    /// The events of a run from (t₀, y₀), every condition evaluated there.
    ///
    /// Errors: [`Error::BadEvent`](crate::Error::BadEvent) when a condition is NaN at (t₀, y₀).
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
            tally: Tally::new(n, max_events, tolerance),
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
    /// Errors: [`Error::BadEvent`](crate::Error::BadEvent) when a condition is NaN there.
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
    /// Errors: [`Error::BadEvent`](crate::Error::BadEvent) when a condition is NaN where a
    /// crossing is sought, or a change leaves the state non-finite or its condition NaN;
    /// [`Error::EventsAccumulate`](crate::Error::EventsAccumulate) when a change event fires
    /// again sooner than the tolerance resolves, or the run's events exceed its `max_events`.
    // The driver's step in its parts (model, dense step, times, states, records): a struct for
    // them would be built and taken apart at the one call site.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn handle<M: crate::Model<State = S>>(
        &mut self,
        model: &M,
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
        let outcome = located.and_then(|()| self.act(model, &found, dense, t1, y1, at, records));
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
                                    return Err(self.tally.accumulating(i, &e.name, t));
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
