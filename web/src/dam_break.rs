//! The SPH dam break: a water column 0.2 m wide and 0.4 m high collapses in a box 1 m wide,
//! weakly compressible SPH at a fixed step, in slow motion.

use odyn::sph::Sph;
use odyn::{Fingerprint, FixedTimestep};
use wasm_bindgen::prelude::*;

use crate::{Js, hex, js};

/// The column's width (m).
const WIDTH: f64 = 0.2;

/// Simulated seconds before the panel starts over: the front reaches the far wall at ~0.35 s and
/// the surge runs up it; at ~0.82 s, on the backwash, one particle of this coarse column
/// escapes over the 0.4 m wall at the start side and odyn's SPH stops the run.
const REPLAY: f64 = 0.7;

/// Particles across the column (288 fluid particles).
const RESOLUTION: usize = 12;

/// Simulated seconds a second of real time.
const SPEED: f64 = 0.25;

/// Steps in [`DamBreakLab::check`].
const CHECK_STEPS: u32 = 200;

/// The dam break panel.
#[wasm_bindgen]
pub struct DamBreakLab {
    sph: Sph,
    /// The step: 0.8 of the stable step at rest, 0.25·h/c₀ (below the bound as long as the
    /// flow stays slower than c₀/4, 2.5 times the fastest flow the sound speed was set for).
    dt: f64,
    steps: u64,
    clock: FixedTimestep,
}

impl DamBreakLab {
    fn clock() -> FixedTimestep {
        let mut clock = FixedTimestep::new();
        clock.max_frame_time = 0.1 * SPEED;
        clock
    }
}

#[wasm_bindgen]
impl DamBreakLab {
    /// The column at rest, about to collapse.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Js<DamBreakLab> {
        let sph = js(scenes::dam_break(WIDTH, RESOLUTION))?;
        let dt = 0.8 * sph.stable_dt();
        Ok(DamBreakLab {
            sph,
            dt,
            steps: 0,
            clock: Self::clock(),
        })
    }

    /// Back to the column at rest.
    pub fn restart(&mut self) -> Js<()> {
        *self = Self::new()?;
        Ok(())
    }

    /// Advances by one display frame of `seconds` (simulated time at a quarter of real time),
    /// starting over once 0.7 s are simulated.
    /// Returns the steps taken.
    pub fn frame(&mut self, seconds: f64) -> Js<u32> {
        if self.t() >= REPLAY {
            self.restart()?;
        }
        let (sph, steps, dt) = (&mut self.sph, &mut self.steps, self.dt);
        let tick = js(self.clock.advance_with(seconds * SPEED, dt, || {
            sph.step(dt)?;
            *steps += 1;
            Ok(())
        }))?;
        Ok(tick.steps as u32)
    }

    /// 200 steps from the column at rest.
    pub fn check(&mut self) -> Js<u32> {
        self.restart()?;
        for _ in 0..CHECK_STEPS {
            js(self.sph.step(self.dt))?;
            self.steps += 1;
        }
        Ok(CHECK_STEPS)
    }

    /// The time, positions, velocities and densities, as sixteen hex digits.
    pub fn fingerprint(&self) -> String {
        let mut hash = Fingerprint::new();
        hash.add(self.t());
        for (x, v) in self.sph.x.iter().zip(&self.sph.v) {
            hash.extend(x.iter().chain(v.iter()));
        }
        hash.extend(self.sph.densities());
        hex(hash.finish())
    }

    /// The method's label.
    pub fn method(&self) -> String {
        "WCSPH, symplectic Euler".to_owned()
    }

    /// The step.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Simulated seconds a real one.
    pub fn speed(&self) -> f64 {
        SPEED
    }

    /// Time.
    pub fn t(&self) -> f64 {
        self.steps as f64 * self.dt
    }

    /// The box: width and height (m).
    pub fn domain(&self) -> Vec<f64> {
        let (w, h) = self.sph.options().domain;
        vec![w, h]
    }

    /// The fluid particles: x, y pairs (m).
    pub fn particles(&self) -> Vec<f64> {
        self.sph.x.iter().flat_map(|x| [x.x, x.y]).collect()
    }

    /// The fluid particles' speeds (m/s).
    pub fn speeds(&self) -> Vec<f64> {
        self.sph.v.iter().map(|v| v.norm()).collect()
    }

    /// How far the front has run (m).
    pub fn front(&self) -> f64 {
        self.sph.front()
    }
}
