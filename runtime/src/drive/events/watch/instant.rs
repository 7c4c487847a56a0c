//! What happens at each instant of a step's located events: records, stops and changes, in
//! the order of the run's event list, and the check of the state a change leaves.

use super::{Found, Latch, Outcome, Watch};
use crate::drive::events::{Action, Trigger};
use crate::drive::{DenseStep, ulp};
use crate::model::Jump;
use crate::trajectory::EventRecord;
use crate::{Error, Result, State};

impl<S: State> Watch<'_, S> {
    /// Takes the located events instant by instant (see [`Watch::handle`]).
    #[allow(
        clippy::too_many_arguments,
        reason = "the step's parts, each one borrowed"
    )]
    pub(super) fn act<M: crate::Model<State = S>>(
        &mut self,
        model: &M,
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
                        let e = &self.events[event];
                        let condition = match &e.trigger {
                            Trigger::Crossing { condition, .. } => Some(&**condition as _),
                            Trigger::Times(_) => None,
                        };
                        let jump = Jump {
                            name: &e.name,
                            condition,
                            change: &**change,
                        };
                        model.complete_change(t, &before, at, jump)?;
                        // The change moved the state off the algebraic equations, perhaps: the
                        // algebraic components follow the differential ones there.
                        model.consistent(t, at, &crate::NewtonOptions::default())?;
                        changed = true;
                    }
                }
                let name = &self.events[event].name;
                let change = matches!(self.events[event].action, Action::Change(_));
                self.tally.count(event, name, change, t)?;
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
}
