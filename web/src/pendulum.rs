//! Two double pendulums released a micro-radian apart: RK4 at dt = 1 ms keeps each one's energy
//! to ~10⁻⁹, and still the two part within seconds — the chaos, not the integrator.

use odyn::integrators::Rk4;
use odyn::{Fingerprint, FixedTimestep, Model, State, Stepper};
use scenes::{DoublePendulum, DoublePendulumState};
use wasm_bindgen::prelude::*;

use crate::{Js, hex, js};

/// The step: 16⅔ RK4 steps a 60 Hz frame.
const DT: f64 = 1e-3;

/// How far apart the two lower angles start (rad).
const NUDGE: f64 = 1e-6;

/// Steps in [`PendulumLab::check`]: 10 s.
const CHECK_STEPS: u32 = 10_000;

/// The double pendulum panel.
#[wasm_bindgen]
pub struct PendulumLab {
    model: &'static DoublePendulum,
    pendulums: [Stepper<'static, DoublePendulum, Rk4<DoublePendulumState>>; 2],
    clock: FixedTimestep,
}

impl PendulumLab {
    /// Both pendulums at their release.
    fn start(
        model: &'static DoublePendulum,
    ) -> odyn::Result<[Stepper<'static, DoublePendulum, Rk4<DoublePendulumState>>; 2]> {
        let mut nudged = model.state();
        nudged.theta2 += NUDGE;
        Ok([
            Stepper::new(model, model.state(), 0.0, DT)?,
            Stepper::new(model, nudged, 0.0, DT)?,
        ])
    }
}

#[wasm_bindgen]
impl PendulumLab {
    /// The `double_pendulum` example's release (θ₁ = 2, θ₂ = 2.5 rad, at rest), and the same with
    /// θ₂ one micro-radian more.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Js<PendulumLab> {
        let model: &'static DoublePendulum = Box::leak(Box::new(DoublePendulum::released()));
        Ok(PendulumLab {
            model,
            pendulums: js(Self::start(model))?,
            clock: FixedTimestep::new(),
        })
    }

    /// Back to the release.
    pub fn restart(&mut self) -> Js<()> {
        self.pendulums = js(Self::start(self.model))?;
        self.clock = FixedTimestep::new();
        Ok(())
    }

    /// Advances both by one display frame of `seconds` (simulated time runs at real time).
    /// Returns the steps taken by each.
    pub fn frame(&mut self, seconds: f64) -> Js<u32> {
        let [a, b] = &mut self.pendulums;
        let tick = js(self.clock.advance_with(seconds, DT, || {
            a.step()?;
            b.step()
        }))?;
        Ok(tick.steps as u32)
    }

    /// 10 s from the release.
    pub fn check(&mut self) -> Js<u32> {
        self.restart()?;
        for _ in 0..CHECK_STEPS {
            for pendulum in &mut self.pendulums {
                js(pendulum.step())?;
            }
        }
        Ok(CHECK_STEPS)
    }

    /// Both pendulums' time and state, as sixteen hex digits.
    pub fn fingerprint(&self) -> String {
        let mut hash = Fingerprint::new();
        for pendulum in &self.pendulums {
            hash.add(pendulum.t());
            hash.extend(pendulum.state().as_slice());
        }
        hex(hash.finish())
    }

    /// The method's label.
    pub fn method(&self) -> String {
        odyn::Method::Rk4.info().label.to_owned()
    }

    /// The step.
    pub fn dt(&self) -> f64 {
        DT
    }

    /// Time.
    pub fn t(&self) -> f64 {
        self.pendulums[0].t()
    }

    /// The bobs of both pendulums, metres from the pivot, y up: x₁, y₁, x₂, y₂ of the first,
    /// then of the second.
    pub fn bobs(&self) -> Vec<f64> {
        use odyn::math::Transcendental as T;
        let (l1, l2) = (self.model.l1, self.model.l2);
        let mut bobs = Vec::with_capacity(8);
        for pendulum in &self.pendulums {
            let s = pendulum.state();
            let (x1, y1) = (l1 * T::sin(s.theta1), -l1 * T::cos(s.theta1));
            bobs.extend([
                x1,
                y1,
                x1 + l2 * T::sin(s.theta2),
                y1 - l2 * T::cos(s.theta2),
            ]);
        }
        bobs
    }

    /// The distance between the two lower bobs (m).
    pub fn separation(&self) -> f64 {
        let b = self.bobs();
        ((b[2] - b[6]).powi(2) + (b[3] - b[7]).powi(2)).sqrt()
    }

    /// The first pendulum's energy drift, |E − E₀|/|E₀|.
    pub fn energy_drift(&self) -> f64 {
        let e0 = Model::energy(self.model, &self.model.state()).unwrap_or(f64::NAN);
        let e = Model::energy(self.model, self.pendulums[0].state()).unwrap_or(f64::NAN);
        ((e - e0) / e0).abs()
    }
}
