//! One attempted step and what follows its acceptance: divergence, events, dense output.

use super::*;

impl<'a, 'm, M: Model, I: Integrator<M>> Driver<'a, 'm, M, I> {
    pub(super) fn attempt(
        &mut self,
        h: f64,
        tolerances: Option<&super::Tolerances>,
    ) -> Result<f64> {
        if self.dirty {
            self.dirty = false;
            self.integrator
                .restart(self.model, self.t, &self.y, &mut self.stats);
            self.watch.restart(self.t, &self.y)?;
            self.f_start = false;
        }
        let step = Step {
            t: self.t,
            h,
            y: &self.y,
            tolerances,
            stats: &mut self.stats,
        };
        self.integrator.attempt(self.model, step, &mut self.y_new)
    }

    /// Accepts the attempt that went from (t, y) to (`t1`, `y_new`): checks for divergence,
    /// handles events and save times, and moves on.
    pub(super) fn accept(&mut self, t1: f64) -> Result<Flow> {
        if let Some((index, value)) = first_outside(&self.y_new, self.limit) {
            return Err(Error::Diverged {
                method: I::METHOD,
                step: self.grid.unwrap_or(self.stats.steps + 1),
                t: t1,
                component: self.y_new.component_name(index),
                value,
                limit: self.limit,
            });
        }
        self.integrator.accept();
        self.stats.steps += 1;
        let events = !self.watch.is_empty() && self.watch.scan(t1, &self.y_new)?;
        let saves = self
            .recording
            .save_at
            .is_some_and(|times| times.get(self.next_save).is_some_and(|&s| s <= t1));
        if events && self.watch.latched() && !self.f_start {
            self.model.derivative(self.t, &self.y, &mut self.ends[0]);
            self.stats.evaluations += 1;
            self.f_start = true;
        }
        let hermite = (events || saves || self.record.dense.is_some()) && self.build_dense(t1);
        let outcome = if events {
            self.watch.handle(
                &self.dense,
                t1,
                &self.y_new,
                &self.ends[0],
                &mut self.at,
                &mut self.record.events,
            )?
        } else {
            self.watch.advance();
            Outcome::Continue
        };
        let (end, flow) = match outcome {
            Outcome::Continue => (t1, Flow::Continue),
            Outcome::Changed(t) => (t, Flow::Changed),
            Outcome::Stop(t) => (t, Flow::Stopped),
        };
        if saves {
            self.save_until(end, flow == Flow::Continue);
        }
        if let Some(store) = &mut self.record.dense {
            store.push(&self.dense, end);
        }
        match flow {
            Flow::Continue => {
                std::mem::swap(&mut self.y, &mut self.y_new);
                self.t = t1;
                // The Hermite interpolant evaluated f at the end: the next step's start.
                if hermite {
                    self.ends.swap(0, 1);
                }
                self.f_start = hermite;
            }
            Flow::Changed | Flow::Stopped => {
                let event_record = self.record.events.last().cloned();
                std::mem::swap(&mut self.y, &mut self.at);
                self.t = end;
                self.f_start = false;
                if !self.quiet
                    && self.recording.save_at.is_none()
                    && let Some(event) = event_record
                {
                    // A discontinuity shows in the samples as two samples at one time.
                    let step = self.sample_step();
                    self.record
                        .samples
                        .push(sample(self.model, step, end, event.before));
                    if flow == Flow::Changed {
                        self.record
                            .samples
                            .push(sample(self.model, step, end, event.after));
                    }
                }
                if flow == Flow::Changed {
                    self.integrator
                        .restart(self.model, self.t, &self.y, &mut self.stats);
                    if let Some(times) = self.recording.save_at
                        && times.get(self.next_save) == Some(&end)
                    {
                        self.push_sample();
                        self.next_save += 1;
                    }
                } else if self.recording.save_at.is_some() {
                    self.finish();
                }
            }
        }
        Ok(flow)
    }

    /// Fills `self.dense` for the step from (t, y) to (t1, y_new): the method's own interpolant,
    /// or the cubic Hermite one through f at both ends (then `ends[1]` holds f(t1, y_new) and
    /// this returns true).
    pub(super) fn build_dense(&mut self, t1: f64) -> bool {
        let h = t1 - self.t;
        let step = Step {
            t: self.t,
            h,
            y: &self.y,
            tolerances: None,
            stats: &mut self.stats,
        };
        if self
            .integrator
            .dense(self.model, step, &self.y_new, &mut self.dense)
        {
            return false;
        }
        let [f0, f1] = &mut self.ends;
        if !self.f_start {
            self.model.derivative(self.t, &self.y, f0);
            self.stats.evaluations += 1;
        }
        self.model.derivative(t1, &self.y_new, f1);
        self.stats.evaluations += 1;
        self.dense
            .hermite(self.t, h, [&self.y, f0, &self.y_new, f1]);
        true
    }
}
