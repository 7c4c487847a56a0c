//! The adaptive loop: step sizes from the controller (or the method), the first step by
//! Hairer's algorithm, landing on the end and on time events.

use super::*;

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
        tolerances.check_against(&self.track.y)?;
        let mut control_state = ControllerState::new(control.controller.unwrap_or(controller));
        let mut h = match control.dt_initial {
            Some(h) => h,
            None => {
                let [f0, scratch] = &mut self.track.ends;
                self.track.model.derivative(self.track.t, &self.track.y, f0);
                self.track.stats.evaluations += 2;
                let h = initial_step(
                    self.track.model,
                    self.track.t,
                    &self.track.y,
                    f0,
                    order,
                    tolerances,
                    control.dt_max,
                    (&mut self.track.at, scratch),
                );
                self.track.f_start = true;
                h
            }
        };
        let mut until_record = self.track.recording.every;
        while self.track.t < t_end {
            let stop = t_end.min(self.track.watch.next_stop());
            let mut h_try = h.min(control.dt_max);
            // Land exactly on the end or a time event; stretch by up to 1 % to get there rather
            // than leave a sliver of a step (Hairer's codes do the same).
            let t1 = if self.track.t + 1.01 * h_try >= stop {
                h_try = stop - self.track.t;
                stop
            } else {
                self.track.t + h_try
            };
            let resolution = 10.0 * ulp(self.track.t);
            let floor = control.dt_min.max(resolution);
            let t = self.track.t;
            let too_small = |dt: f64| Error::StepSizeTooSmall {
                t,
                dt,
                dt_min: control.dt_min,
                resolution,
            };
            if h_try < floor && t1 != stop {
                return Err(too_small(h_try));
            }
            if self.track.stats.steps + self.track.stats.rejected >= control.max_steps {
                return Err(Error::MaxSteps {
                    t: self.track.t,
                    steps: control.max_steps,
                });
            }
            // A method that sizes its own steps (`Integrator::next_step`) overrides the
            // controller after each outcome; the caps and landings above still apply.
            match self.attempt(h_try, Some(tolerances)) {
                Ok(err) if err <= 1.0 => {
                    let controlled = control_state.accepted(h_try, err);
                    let flow = self.accept(t1)?;
                    h = self.integrator.next_step().unwrap_or(controlled);
                    if flow == Flow::Stopped {
                        return Ok(());
                    }
                    if !self.track.quiet
                        && self.track.recording.save_at.is_none()
                        && flow == Flow::Continue
                    {
                        until_record -= 1;
                        if until_record == 0 || self.track.t >= t_end {
                            self.track.push_sample();
                            until_record = self.track.recording.every;
                            self.track.report(t_end);
                        }
                    }
                }
                Ok(err) => {
                    self.track.stats.rejected += 1;
                    let controlled = control_state.rejected(h_try, err);
                    h = self.integrator.next_step().unwrap_or(controlled);
                    if h < floor {
                        return Err(too_small(h));
                    }
                }
                Err(error) if error.is_retriable() => {
                    self.track.stats.rejected += 1;
                    h = self.integrator.next_step().unwrap_or(0.25 * h_try);
                }
                Err(error) => return Err(error),
            }
        }
        self.track.finish();
        Ok(())
    }
}
