//! [`FixedTimestep`]: the accumulator that drives a fixed-dt model from a variable frame rate.
//!
//! The pattern of Glenn Fiedler's "Fix Your Timestep!" (2004): each frame adds its (capped)
//! duration to an accumulator, whole steps of dt are taken while it lasts, and the remainder as
//! a fraction of dt, `alpha`, is what a renderer interpolates with. The physics only ever sees dt,
//! so a 30 fps and a 144 fps loop produce bit-identical states after equal numbers of steps.

use crate::{Error, Integrator, Model, Result, Stepper};

/// What one frame did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tick {
    /// Steps taken this frame.
    pub steps: u64,
    /// The time left in the accumulator as a fraction of dt, in [0, 1): render
    /// `previous·(1 − alpha) + current·alpha`.
    pub alpha: f64,
    /// Seconds of this frame's time that were not simulated: cut by
    /// [`FixedTimestep::max_frame_time`], or left over when [`FixedTimestep::max_steps_per_frame`]
    /// stopped the catch-up. The simulation then runs slower than real time instead of
    /// spiralling.
    pub dropped: f64,
}

/// A fixed-timestep accumulator for real-time loops.
#[derive(Clone, Debug, PartialEq)]
pub struct FixedTimestep {
    /// The longest frame time taken into account, in seconds: finite and positive (default 0.1).
    /// A longer frame (a breakpoint, a stalled window) is clipped so the loop does not spiral
    /// trying to catch up.
    pub max_frame_time: f64,
    /// The most steps one frame takes, at least 1 (default 1000): the "spiral of death" guard
    /// for a dt far below the frame time, where catching up would take longer than the frame.
    pub max_steps_per_frame: u64,
    accumulator: f64,
}

impl Default for FixedTimestep {
    fn default() -> Self {
        FixedTimestep {
            max_frame_time: 0.1,
            max_steps_per_frame: 1000,
            accumulator: 0.0,
        }
    }
}

impl FixedTimestep {
    /// An accumulator with the default caps (0.1 s a frame, 1000 steps a frame).
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds one frame of `frame_time` seconds and takes as many whole steps as fit, within the
    /// caps.
    ///
    /// Errors with [`Error::InvalidInput`] for a negative or non-finite frame time, a
    /// `max_frame_time` that is not finite and positive, or `max_steps_per_frame` = 0; and passes
    /// on a divergence from the stepper.
    pub fn advance<M: Model, I: Integrator<M>>(
        &mut self,
        frame_time: f64,
        stepper: &mut Stepper<'_, M, I>,
    ) -> Result<Tick> {
        let dt = stepper.dt();
        self.advance_with(frame_time, dt, || stepper.step())
    }

    /// [`FixedTimestep::advance`] for whatever `step` advances by `dt`: several steppers at once,
    /// an [`crate::xpbd::Xpbd`] or [`crate::sph::Sph`] system, a user's drag applied before
    /// each step.
    ///
    /// Errors: as [`FixedTimestep::advance`], and [`Error::InvalidInput`] for a `dt` that is not
    /// finite and positive; passes on the first error of `step` (the steps before it stand).
    pub fn advance_with(
        &mut self,
        frame_time: f64,
        dt: f64,
        mut step: impl FnMut() -> Result<()>,
    ) -> Result<Tick> {
        if !(frame_time.is_finite() && frame_time >= 0.0) {
            return Err(Error::invalid(
                "frame_time",
                format!("must be finite and non-negative, got {frame_time:?}"),
            ));
        }
        if !(dt.is_finite() && dt > 0.0) {
            return Err(Error::invalid(
                "dt",
                format!("must be finite and positive, got {dt:?}"),
            ));
        }
        if !(self.max_frame_time.is_finite() && self.max_frame_time > 0.0) {
            return Err(Error::invalid(
                "max_frame_time",
                format!("must be finite and positive, got {:?}", self.max_frame_time),
            ));
        }
        if self.max_steps_per_frame == 0 {
            return Err(Error::invalid("max_steps_per_frame", "must be at least 1"));
        }
        let taken = frame_time.min(self.max_frame_time);
        let mut dropped = frame_time - taken;
        self.accumulator += taken;
        let mut steps = 0;
        while self.accumulator >= dt {
            if steps == self.max_steps_per_frame {
                // Drop the whole steps that are left; keep the fraction for `alpha`.
                let left = (self.accumulator / dt).floor() * dt;
                dropped += left;
                self.accumulator = (self.accumulator - left).max(0.0);
                break;
            }
            step()?;
            self.accumulator -= dt;
            steps += 1;
        }
        Ok(Tick {
            steps,
            alpha: (self.accumulator / dt).clamp(0.0, 1.0 - f64::EPSILON),
            dropped,
        })
    }

    /// Time carried over to the next frame, in seconds.
    pub fn leftover(&self) -> f64 {
        self.accumulator
    }
}
