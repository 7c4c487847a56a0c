//! Jelly, water and snow by the material point method (MLS-MPM), on a 64² grid, in slow motion.

use odyn::hybrid::mpm::{Material, Mpm};
use odyn::{Error, Fingerprint, FixedTimestep};
use wasm_bindgen::prelude::*;

use crate::{Js, hex, js};

/// Grid nodes a side of the unit box (2 952 particles).
const GRID: usize = 64;

/// Simulated time a tick of the panel's clock covers (s): each tick takes as many equal
/// substeps as [`Mpm::stable_dt`] asks for, so the clock's step is fixed while MPM's stable step
/// shrinks as snow compacts and hardens.
const TICK: f64 = 2e-3;

/// Simulated seconds before the panel starts over.
const REPLAY: f64 = 1.5;

/// Simulated seconds a second of real time.
const SPEED: f64 = 0.25;

/// Ticks in [`MpmLab::check`].
const CHECK_TICKS: u32 = 50;

/// The MPM panel.
#[wasm_bindgen]
pub struct MpmLab {
    run: Run,
    clock: FixedTimestep,
    /// The energy at rest.
    energy: f64,
}

/// The simulation and its counts.
struct Run {
    mpm: Mpm,
    ticks: u64,
    substeps: u64,
}

impl Run {
    /// One tick: ⌈TICK/stable dt⌉ equal substeps.
    fn tick(&mut self) -> odyn::Result<()> {
        let limit = self.mpm.stable_dt();
        let count = (TICK / limit).ceil();
        if !(count.is_finite() && count <= 10_000.0) {
            return Err(Error::InvalidInput {
                field: "dt".into(),
                reason: format!(
                    "the stable step {limit:e} s needs more than 10 000 substeps a tick"
                ),
            });
        }
        let count = (count as u64).max(1);
        for _ in 0..count {
            self.mpm.step(TICK / count as f64)?;
        }
        self.ticks += 1;
        self.substeps += count;
        Ok(())
    }
}

#[wasm_bindgen]
impl MpmLab {
    /// Water on the left, jelly and snow above, at rest.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Js<MpmLab> {
        let (mpm, _) = js(scenes::hybrid::jelly_water_snow(GRID))?;
        let mut clock = FixedTimestep::new();
        clock.max_frame_time = 0.1 * SPEED;
        Ok(MpmLab {
            energy: mpm.energy(),
            run: Run {
                mpm,
                ticks: 0,
                substeps: 0,
            },
            clock,
        })
    }

    /// Back to the start.
    pub fn restart(&mut self) -> Js<()> {
        *self = Self::new()?;
        Ok(())
    }

    /// Advances by one display frame of `seconds` (simulated at a quarter of real time),
    /// starting over once 1.5 s are simulated. Returns the ticks taken.
    pub fn frame(&mut self, seconds: f64) -> Js<u32> {
        if self.t() >= REPLAY {
            self.restart()?;
        }
        let run = &mut self.run;
        let tick = js(self
            .clock
            .advance_with(seconds * SPEED, TICK, || run.tick()))?;
        Ok(tick.steps as u32)
    }

    /// 50 ticks (0.1 s) from the start.
    pub fn check(&mut self) -> Js<u32> {
        self.restart()?;
        for _ in 0..CHECK_TICKS {
            js(self.run.tick())?;
        }
        Ok(CHECK_TICKS)
    }

    /// The time, positions, velocities, deformation gradients and volume ratios, as sixteen
    /// hex digits.
    pub fn fingerprint(&self) -> String {
        let mut hash = Fingerprint::new();
        hash.add(self.t());
        for (x, v) in self.run.mpm.x.iter().zip(&self.run.mpm.v) {
            hash.extend(x.iter().chain(v.iter()));
        }
        for f in self.run.mpm.deformation() {
            hash.extend(f.iter());
        }
        hash.extend(self.run.mpm.volume_ratios());
        hex(hash.finish())
    }

    /// The method's label.
    pub fn method(&self) -> String {
        format!(
            "MLS-MPM, APIC, {:.1} substeps a tick",
            self.run.substeps as f64 / self.run.ticks.max(1) as f64
        )
    }

    /// The panel clock's step: a tick (s).
    pub fn dt(&self) -> f64 {
        TICK
    }

    /// Simulated seconds a real one.
    pub fn speed(&self) -> f64 {
        SPEED
    }

    /// Time (s).
    pub fn t(&self) -> f64 {
        self.run.ticks as f64 * TICK
    }

    /// The particles: x, y pairs (m) in the unit box.
    pub fn particles(&self) -> Vec<f64> {
        self.run.mpm.x.iter().flat_map(|x| [x.x, x.y]).collect()
    }

    /// Each particle's material: 0 water, 1 jelly, 2 snow.
    pub fn materials(&self) -> Vec<u8> {
        let kinds: Vec<u8> = self
            .run
            .mpm
            .materials()
            .iter()
            .map(|m| match m {
                Material::Fluid(_) => 0,
                Material::Elastic(_) => 1,
                Material::Snow(_) => 2,
            })
            .collect();
        (0..self.run.mpm.x.len())
            .map(|p| kinds[self.run.mpm.material_of(p)])
            .collect()
    }

    /// The total energy now over the energy at rest: what the transfers and snow's plasticity
    /// have dissipated.
    pub fn energy_left(&self) -> f64 {
        self.run.mpm.energy() / self.energy
    }
}
