//! How often each event of a run fired: against the run's budget of events, and against the
//! accumulation of changes at one time (Zeno behaviour).

use crate::drive::ulp;
use crate::{Error, Result};

/// Per event, how often it fired and when it last changed the state; all events together
/// against `max_events`.
pub(super) struct Tally {
    fired: Vec<(u64, f64)>,
    total: u64,
    max_events: u64,
    tolerance: f64,
}

impl Tally {
    pub(super) fn new(events: usize, max_events: u64, tolerance: f64) -> Self {
        Tally {
            fired: vec![(0, f64::NEG_INFINITY); events],
            total: 0,
            max_events,
            tolerance,
        }
    }

    /// Counts a firing of event `event` (named `name`) at `t`. A `change` that comes back
    /// sooner than the tolerance resolves is an accumulation of events.
    ///
    /// Errors: [`Error::EventsAccumulate`] for such a change, and past `max_events`.
    pub(super) fn count(&mut self, event: usize, name: &str, change: bool, t: f64) -> Result<()> {
        self.total += 1;
        let (count, last) = &mut self.fired[event];
        *count += 1;
        let window = self.tolerance.max(4.0 * ulp(t));
        if change {
            if t - *last <= window {
                return Err(self.accumulating(event, name, t));
            }
            *last = t;
        }
        if self.total > self.max_events {
            return Err(Error::EventsAccumulate {
                event: name.to_owned(),
                count: self.fired[event].0,
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

    /// The error for the changes of event `event` (named `name`) accumulating at `t`.
    pub(super) fn accumulating(&self, event: usize, name: &str, t: f64) -> Error {
        Error::EventsAccumulate {
            event: name.to_owned(),
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
}
