//! Recording: samples at the recording interval and save times, the end of a run, progress.

use super::*;

impl<M: Model> Track<'_, '_, M> {
    /// Records the save times up to `end` (inclusive when the step went through to it).
    pub(super) fn save_until(&mut self, end: f64, inclusive: bool) {
        let Some(times) = self.recording.save_at else {
            return;
        };
        while let Some(&s) = times.get(self.next_save) {
            if s > end || (!inclusive && s == end) {
                break;
            }
            let state = if s == end {
                self.y_new.clone()
            } else {
                self.dense
                    .eval((s - self.dense.t) / self.dense.h, &mut self.saved);
                self.saved.clone()
            };
            let step = self.sample_step();
            self.record.samples.push(sample(self.model, step, s, state));
            self.next_save += 1;
        }
        self.report(times.last().copied().unwrap_or(end));
    }

    pub(super) fn push_sample(&mut self) {
        let (step, state) = (self.sample_step(), self.y.clone());
        self.record
            .samples
            .push(sample(self.model, step, self.t, state));
    }

    /// The step number a sample carries: the grid step of a fixed-step run, the accepted steps
    /// of an adaptive one.
    pub(super) fn sample_step(&self) -> u64 {
        self.grid.unwrap_or(self.stats.steps)
    }

    /// The last sample, if the loop did not record it already.
    pub(super) fn finish(&mut self) {
        if self.quiet {
            return;
        }
        let recorded = self.record.samples.last().is_some_and(|s| s.t == self.t);
        if !recorded {
            self.push_sample();
        }
    }

    pub(super) fn report(&self, t_end: f64) {
        if let Some(report) = self.recording.progress {
            report(&Progress {
                t: self.t,
                t0: self.t0,
                t_end,
                steps: self.stats.steps,
            });
        }
    }
}

pub(super) fn sample<M: Model>(model: &M, step: u64, t: f64, state: M::State) -> Sample<M::State> {
    Sample {
        step,
        t,
        energy: model.energy(&state),
        state,
    }
}
