//! The adaptive loop: step sizes from the controller (or the method), the first step by
//! Hairer's algorithm, landing on the end and on time events.

use super::*;
use crate::error::Rejection;
use crate::{Error, Method};

impl<'a, 'm, M: Model, I: Integrator<M>> Driver<'a, 'm, M, I> {
    /// Steps adaptively until `t_end`, keeping the error estimate of every step within
    /// `tolerances`; `order` is the method's, for the first step. The tolerances and `control`
    /// come checked against the run (`RunOptions::check`); here the tolerances are checked
    /// against the state, once it is known to be finite.
    pub(crate) fn run_adaptive(
        &mut self,
        t_end: f64,
        tolerances: &super::Tolerances,
        control: &AdaptiveOptions,
        controller: Controller,
        order: u32,
    ) -> Result<()> {
        let mut h = self.track.first_step(tolerances, control, order)?;
        let mut control_state = ControllerState::new(control.controller.unwrap_or(controller));
        let mut until_record = self.track.recording.every;
        let mut rejection = Rejection::None;
        while self.track.t < t_end {
            let aim = self.track.aim(h, t_end, control, (I::METHOD, rejection))?;
            // A method that sizes its own steps (`Integrator::next_step`) overrides the
            // controller after each outcome; the caps and landings of `aim` still apply.
            match self.attempt(aim.h, Some(tolerances)) {
                Ok(err) if err <= 1.0 => {
                    let controlled = control_state.accepted(aim.h, err);
                    let flow = self.accept(aim.t1)?;
                    h = self.integrator.next_step().unwrap_or(controlled);
                    if flow == Flow::Stopped {
                        return Ok(());
                    }
                    self.track.record_step(flow, &mut until_record, t_end);
                }
                Ok(err) => {
                    self.track.stats.rejected += 1;
                    rejection = Rejection::ErrorTest;
                    let controlled = control_state.rejected(aim.h, err);
                    h = self.integrator.next_step().unwrap_or(controlled);
                    if h < aim.floor {
                        return Err(self.track.too_small(h, control, (I::METHOD, rejection)));
                    }
                }
                Err(error) if error.is_retriable() => {
                    self.track.stats.rejected += 1;
                    rejection = match error {
                        Error::SingularMatrix { .. } => Rejection::SingularMatrix,
                        _ => Rejection::Newton,
                    };
                    // Tried at the floor already (the resolution of t, or dt_min): there is no
                    // smaller step to retry with, and retrying the same one would spend the
                    // step budget in place.
                    if aim.h <= aim.floor {
                        return Err(self.track.too_small(aim.h, control, (I::METHOD, rejection)));
                    }
                    h = self.integrator.next_step().unwrap_or(0.25 * aim.h);
                }
                Err(error) => return Err(error),
            }
        }
        self.track.finish();
        Ok(())
    }
}

/// The next attempt of an adaptive run.
pub(super) struct Aim {
    /// Its size.
    h: f64,
    /// Its end.
    t1: f64,
    /// The smallest step allowed from here.
    floor: f64,
}

impl<M: Model> Track<'_, '_, M> {
    /// The first step: `control`'s, or Hairer's estimate for a method of `order` (f at the start
    /// then in `ends[0]`). Checks the tolerances against the state first.
    fn first_step(
        &mut self,
        tolerances: &super::Tolerances,
        control: &AdaptiveOptions,
        order: u32,
    ) -> Result<f64> {
        tolerances.check_against(&self.y)?;
        if let Some(h) = control.dt_initial {
            return Ok(h);
        }
        let [f0, scratch] = &mut self.ends;
        self.model.derivative(self.t, &self.y, f0);
        self.stats.evaluations += 2;
        let h = initial_step(
            self.model,
            self.t,
            &self.y,
            f0,
            order,
            tolerances,
            control.dt_max,
            (&mut self.at, scratch),
        );
        self.f_start = true;
        Ok(h)
    }

    /// The next attempt from the proposed size `h`: capped by `dt_max`, landing exactly on the
    /// end or a time event (stretched by up to 1 % to get there rather than leave a sliver of a
    /// step, as Hairer's codes do). Errors when the step collapsed below its floor or the step
    /// budget ran out.
    fn aim(
        &self,
        h: f64,
        t_end: f64,
        control: &AdaptiveOptions,
        why: (Method, Rejection),
    ) -> Result<Aim> {
        let stop = t_end.min(self.watch.next_stop());
        // A proposal below the resolution of t (a low-order first step at t = 1e12) is tried at
        // the resolution: only a step rejected there has nowhere smaller to go (`run_adaptive`).
        let floor = control.dt_min.max(10.0 * ulp(self.t));
        let mut h = h.max(10.0 * ulp(self.t)).min(control.dt_max);
        let t1 = if self.t + 1.01 * h >= stop {
            h = stop - self.t;
            stop
        } else {
            self.t + h
        };
        if h < floor && t1 != stop {
            return Err(self.too_small(h, control, why));
        }
        if self.stats.steps + self.stats.rejected >= control.max_steps {
            let accepted = self.stats.steps;
            return Err(Error::MaxSteps {
                method: why.0,
                t: self.t,
                t_end,
                mean_step: if accepted > 0 {
                    (self.t - self.t0) / accepted as f64
                } else {
                    f64::NAN
                },
                steps: control.max_steps,
            });
        }
        Ok(Aim { h, t1, floor })
    }

    /// The error for a step of `dt` from the current time, below its floor, of `method` after
    /// a `rejection`.
    fn too_small(
        &self,
        dt: f64,
        control: &AdaptiveOptions,
        (method, rejection): (Method, Rejection),
    ) -> Error {
        Error::StepSizeTooSmall {
            method,
            t: self.t,
            dt,
            dt_min: control.dt_min,
            resolution: 10.0 * ulp(self.t),
            rejection,
        }
    }

    /// Records an accepted step's end at the recording interval (and the last step's).
    #[inline]
    fn record_step(&mut self, flow: Flow, until_record: &mut u64, t_end: f64) {
        if !self.quiet && self.recording.save_at.is_none() && flow == Flow::Continue {
            *until_record -= 1;
            if *until_record == 0 || self.t >= t_end {
                self.push_sample();
                *until_record = self.recording.every;
                self.report(t_end);
            }
        }
    }
}
