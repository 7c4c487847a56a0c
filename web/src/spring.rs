//! The spring lab: m·ẍ = −k·x with k = m = 1 (ω = 1), released from x = 1 at rest, so the exact
//! motion is x = cos t and the energy stays ½.

use odyn::{Fingerprint, FixedTimestep, Method, Model, State};
use scenes::{UndampedSpring, UndampedSpringState};
use wasm_bindgen::prelude::*;

use crate::run::{Run, stepper};
use crate::{Js, hex, js};

/// The methods the panel offers, in its menu's order.
const METHODS: [Method; 7] = [
    Method::ExplicitEuler,
    Method::SymplecticEuler,
    Method::VelocityVerlet,
    Method::Leapfrog,
    Method::Rk4,
    Method::Yoshida4,
    Method::ImplicitEuler,
];

/// dt at the start: explicit Euler's energy grows ×(1 + dt²) = ×1.0004 a step, doubling in
/// 29 s of simulated time.
const DEFAULT_DT: f64 = 0.02;

/// Steps of each method in [`SpringLab::check`].
const CHECK_STEPS: u32 = 1000;

/// The spring lab panel.
#[wasm_bindgen]
pub struct SpringLab {
    model: &'static UndampedSpring,
    run: Box<dyn Run<UndampedSpringState>>,
    clock: FixedTimestep,
    method: Method,
    dt: f64,
    steps: u64,
    /// The states [`SpringLab::check`] ended each method at, folded in.
    checked: Fingerprint,
}

impl SpringLab {
    /// A stepper of `method` at `dt` from the release.
    fn start(&mut self, method: Method, dt: f64) -> odyn::Result<()> {
        self.run = stepper!(method, self.model, self.model.state(), dt;
            ExplicitEuler | SymplecticEuler | VelocityVerlet | Leapfrog | Rk4 | Yoshida4
            | ImplicitEuler)?;
        (self.method, self.dt, self.steps) = (method, dt, 0);
        self.clock = FixedTimestep::new();
        Ok(())
    }
}

#[wasm_bindgen]
impl SpringLab {
    /// Explicit Euler at dt = 0.02 from x = 1, v = 0.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Js<SpringLab> {
        let model: &'static UndampedSpring = Box::leak(Box::new(UndampedSpring {
            x: 1.0,
            v: 0.0,
            k: 1.0,
            m: 1.0,
        }));
        let start =
            || stepper!(Method::ExplicitEuler, model, model.state(), DEFAULT_DT; ExplicitEuler);
        Ok(SpringLab {
            model,
            run: js(start())?,
            clock: FixedTimestep::new(),
            method: Method::ExplicitEuler,
            dt: DEFAULT_DT,
            steps: 0,
            checked: Fingerprint::new(),
        })
    }

    /// The offered methods' names (`explicit_euler`, …), in menu order.
    pub fn methods() -> Vec<String> {
        METHODS.iter().map(|m| m.info().name.to_owned()).collect()
    }

    /// The offered methods' labels (`Explicit Euler`, …), in menu order.
    pub fn labels() -> Vec<String> {
        METHODS.iter().map(|m| m.info().label.to_owned()).collect()
    }

    /// Restarts from the release with method `name` (one of [`SpringLab::methods`]) and `dt`.
    pub fn restart(&mut self, name: &str, dt: f64) -> Js<()> {
        let method: Method = js(name.parse())?;
        self.checked = Fingerprint::new();
        js(self.start(method, dt))
    }

    /// Advances by one display frame of `seconds`: the whole steps of dt that fit (simulated
    /// time runs at real time). Returns the steps taken.
    pub fn frame(&mut self, seconds: f64) -> Js<u32> {
        let (run, steps) = (&mut self.run, &mut self.steps);
        let tick = js(self.clock.advance_with(seconds, self.dt, || {
            run.step()?;
            *steps += 1;
            Ok(())
        }))?;
        Ok(tick.steps as u32)
    }

    /// Every offered method, 1 000 steps each from the release at dt = 0.02, into one
    /// fingerprint; leaves the panel on the last method.
    pub fn check(&mut self) -> Js<u32> {
        self.checked = Fingerprint::new();
        for method in METHODS {
            js(self.start(method, DEFAULT_DT))?;
            for _ in 0..CHECK_STEPS {
                js(self.run.step())?;
            }
            self.steps = u64::from(CHECK_STEPS);
            self.checked.add(self.run.t());
            self.checked.extend(self.run.state().as_slice());
        }
        Ok(CHECK_STEPS * METHODS.len() as u32)
    }

    /// The states the last check ended at (if any since the last restart), then the time and
    /// the state, as sixteen hex digits.
    pub fn fingerprint(&self) -> String {
        let mut hash = self.checked;
        hash.add(self.run.t());
        hash.extend(self.run.state().as_slice());
        hex(hash.finish())
    }

    /// The method's label.
    pub fn method(&self) -> String {
        self.method.info().label.to_owned()
    }

    /// The step.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Steps since the start.
    pub fn steps(&self) -> f64 {
        self.steps as f64
    }

    /// Time.
    pub fn t(&self) -> f64 {
        self.run.t()
    }

    /// Position.
    pub fn x(&self) -> f64 {
        self.run.state().x
    }

    /// Velocity.
    pub fn v(&self) -> f64 {
        self.run.state().v
    }

    /// Energy ½m·v² + ½k·x² (½ at the start and forever, exactly).
    pub fn energy(&self) -> f64 {
        Model::energy(self.model, self.run.state()).unwrap_or(f64::NAN)
    }

    /// The exact position at `t`: cos t.
    pub fn exact(t: f64) -> f64 {
        odyn::math::Transcendental::cos(t)
    }

    /// The energy's measured growth per step, (E/E₀)^(1/n) (1 before the first step).
    pub fn growth_per_step(&self) -> f64 {
        if self.steps == 0 {
            return 1.0;
        }
        let ratio = self.energy() / 0.5;
        odyn::math::Transcendental::powf(ratio, 1.0 / self.steps as f64)
    }

    /// Explicit Euler's growth per step on this spring, 1 + ω²dt² = 1 + dt²: each step maps
    /// (x, v) by a matrix of determinant 1 + dt² that is a rotation times √(1 + dt²)
    /// (the seeds' spring lab).
    pub fn explicit_euler_growth(&self) -> f64 {
        1.0 + self.dt * self.dt
    }
}
