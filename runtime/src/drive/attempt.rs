//! One attempted step and its acceptance: the method's parts of it; the rest (divergence,
//! events, save times, dense output) is the track's.

use super::*;

impl<'a, 'm, M: Model, I: Integrator<M>> Driver<'a, 'm, M, I> {
    pub(super) fn attempt(
        &mut self,
        h: f64,
        tolerances: Option<&super::Tolerances>,
    ) -> Result<f64> {
        let track = &mut self.track;
        if track.dirty {
            track.dirty = false;
            self.integrator
                .restart(track.model, track.t, &track.y, &mut track.stats);
            track.watch.restart(track.t, &track.y)?;
            track.f_start = false;
        }
        let step = Step {
            t: track.t,
            h,
            y: &track.y,
            tolerances,
            stats: &mut track.stats,
        };
        self.integrator.attempt(track.model, step, &mut track.y_new)
    }

    /// Accepts the attempt that went from (t, y) to (`t1`, `y_new`): checks for divergence,
    /// handles events and save times, and moves on.
    pub(super) fn accept(&mut self, t1: f64) -> Result<Flow> {
        self.track.check_limit(t1, I::METHOD)?;
        self.integrator.accept();
        let (events, saves) = self.track.scan(t1)?;
        let hermite = self.track.looks_inside(events, saves) && self.build_dense(t1);
        let flow = self.track.conclude(t1, (events, saves), hermite)?;
        if flow == Flow::Changed {
            let track = &mut self.track;
            self.integrator
                .restart(track.model, track.t, &track.y, &mut track.stats);
        }
        Ok(flow)
    }

    /// Fills the track's dense step for the step from (t, y) to (t1, y_new): the method's own
    /// interpolant, or the cubic Hermite one through f at both ends (then `ends[1]` holds
    /// f(t1, y_new) and this returns true).
    pub(super) fn build_dense(&mut self, t1: f64) -> bool {
        let track = &mut self.track;
        let step = Step {
            t: track.t,
            h: t1 - track.t,
            y: &track.y,
            tolerances: None,
            stats: &mut track.stats,
        };
        if self
            .integrator
            .dense(track.model, step, &track.y_new, &mut track.dense)
        {
            return false;
        }
        track.hermite(t1);
        true
    }
}
