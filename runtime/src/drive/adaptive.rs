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
        tolerances.check_against(&self.y)?;
        let mut control_state = ControllerState::new(control.controller.unwrap_or(controller));
        let mut h = match control.dt_initial {
            Some(h) => h,
            None => {
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
                h
            }
        };
        let mut until_record = self.recording.every;
        while self.t < t_end {
            let stop = t_end.min(self.watch.next_stop());
            let mut h_try = h.min(control.dt_max);
            // Land exactly on the end or a time event; stretch by up to 1 % to get there rather
            // than leave a sliver of a step (Hairer's codes do the same).
            let t1 = if self.t + 1.01 * h_try >= stop {
                h_try = stop - self.t;
                stop
            } else {
                self.t + h_try
            };
            let resolution = 10.0 * ulp(self.t);
            let floor = control.dt_min.max(resolution);
            let t = self.t;
            let too_small = |dt: f64| Error::StepSizeTooSmall {
                t,
                dt,
                dt_min: control.dt_min,
                resolution,
            };
            if h_try < floor && t1 != stop {
                return Err(too_small(h_try));
            }
            if self.stats.steps + self.stats.rejected >= control.max_steps {
                return Err(Error::MaxSteps {
                    t: self.t,
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
                    if !self.quiet && self.recording.save_at.is_none() && flow == Flow::Continue {
                        until_record -= 1;
                        if until_record == 0 || self.t >= t_end {
                            self.push_sample();
                            until_record = self.recording.every;
                            self.report(t_end);
                        }
                    }
                }
                Ok(err) => {
                    self.stats.rejected += 1;
                    let controlled = control_state.rejected(h_try, err);
                    h = self.integrator.next_step().unwrap_or(controlled);
                    if h < floor {
                        return Err(too_small(h));
                    }
                }
                Err(error) if error.is_retriable() => {
                    self.stats.rejected += 1;
                    h = self.integrator.next_step().unwrap_or(0.25 * h_try);
                }
                Err(error) => return Err(error),
            }
        }
        self.finish();
        Ok(())
    }
}
