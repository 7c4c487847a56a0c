//! Gray–Scott reaction–diffusion on 128² cells of Pearson's size (the middle of his 256² grid,
//! periodic), explicit Euler at dt = 1 (0.84 of diffusion's limit dx²/4D_u = 1.19), with the
//! named patterns.

use odyn::grid::GridState;
use odyn::integrators::ExplicitEuler;
use odyn::{Fingerprint, FixedTimestep, Method, Model, State, Stepper};
use scenes::GrayScott;
use wasm_bindgen::prelude::*;

use crate::{Js, hex, js};

/// Cells a side.
const SIDE: usize = 128;

/// The step (model time units).
const DT: f64 = 1.0;

/// Model time a second of real time: 33⅓ steps a 60 Hz frame.
const SPEED: f64 = 2000.0;

/// Steps in [`GrayScottLab::check`].
const CHECK_STEPS: u32 = 500;

/// The Gray–Scott panel.
#[wasm_bindgen]
pub struct GrayScottLab {
    /// The model of each pattern shown so far (leaked: a stepper borrows its model).
    models: [Option<&'static GrayScott>; GrayScott::PATTERNS.len()],
    pattern: usize,
    run: Stepper<'static, GrayScott, ExplicitEuler<GridState>>,
    clock: FixedTimestep,
}

impl GrayScottLab {
    /// Pattern `k`'s model, made the first time it is asked for.
    fn model(&mut self, k: usize) -> odyn::Result<&'static GrayScott> {
        if let Some(model) = self.models[k] {
            return Ok(model);
        }
        let model: &'static GrayScott = Box::leak(Box::new(pattern(k)?));
        self.models[k] = Some(model);
        Ok(model)
    }

    /// A clock that runs model time at [`SPEED`], caught up over at most 0.1 s of real time.
    fn clock() -> FixedTimestep {
        let mut clock = FixedTimestep::new();
        clock.max_frame_time = 0.1 * SPEED;
        clock
    }
}

#[wasm_bindgen]
impl GrayScottLab {
    /// Pearson's start (a square of u = ½, v = ¼ in u = 1, v = 0) under the first pattern.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Js<GrayScottLab> {
        let model: &'static GrayScott = Box::leak(Box::new(js(pattern(0))?));
        let mut models = [None; GrayScott::PATTERNS.len()];
        models[0] = Some(model);
        Ok(GrayScottLab {
            models,
            pattern: 0,
            run: js(Stepper::new(model, model.state(), 0.0, DT))?,
            clock: Self::clock(),
        })
    }

    /// The patterns' names, with their feed and kill rates: `mitosis (F = 0.0367, k = 0.0649)`.
    pub fn patterns() -> Vec<String> {
        GrayScott::PATTERNS
            .iter()
            .map(|(name, feed, kill)| format!("{name} (F = {feed}, k = {kill})"))
            .collect()
    }

    /// Restarts from Pearson's start under pattern `k`.
    pub fn restart(&mut self, k: usize) -> Js<()> {
        if k >= GrayScott::PATTERNS.len() {
            return Err(format!(
                "there are {} patterns; got pattern {k}",
                GrayScott::PATTERNS.len()
            ));
        }
        let model = js(self.model(k))?;
        self.run = js(Stepper::new(model, model.state(), 0.0, DT))?;
        self.pattern = k;
        self.clock = Self::clock();
        Ok(())
    }

    /// Advances by one display frame of `seconds`. Returns the steps taken.
    pub fn frame(&mut self, seconds: f64) -> Js<u32> {
        let run = &mut self.run;
        let tick = js(self.clock.advance_with(seconds * SPEED, DT, || run.step()))?;
        Ok(tick.steps as u32)
    }

    /// 500 steps of the first pattern.
    pub fn check(&mut self) -> Js<u32> {
        self.restart(0)?;
        for _ in 0..CHECK_STEPS {
            js(self.run.step())?;
        }
        Ok(CHECK_STEPS)
    }

    /// The time and both fields, as sixteen hex digits.
    pub fn fingerprint(&self) -> String {
        let mut hash = Fingerprint::new();
        hash.add(self.run.t());
        hash.extend(self.run.state().as_slice());
        hex(hash.finish())
    }

    /// The method's label.
    pub fn method(&self) -> String {
        Method::ExplicitEuler.info().label.to_owned()
    }

    /// The step.
    pub fn dt(&self) -> f64 {
        DT
    }

    /// Model time per second of real time.
    pub fn speed(&self) -> f64 {
        SPEED
    }

    /// Time.
    pub fn t(&self) -> f64 {
        self.run.t()
    }

    /// Cells a side.
    pub fn side(&self) -> usize {
        SIDE
    }

    /// The activator v as RGBA pixels, row by row: dark blue at v = 0 through teal to pale
    /// yellow at v ≥ 0.4.
    pub fn pixels(&self) -> Vec<u8> {
        let v = GridState::field(self.run.state(), 1);
        v.iter().flat_map(|&v| colour(v / 0.4)).collect()
    }
}

/// Pearson's start under pattern `k`, on cells of his size: D_u·dt/dx² = 0.21.
fn pattern(k: usize) -> odyn::Result<GrayScott> {
    let (_, feed, kill) = GrayScott::PATTERNS[k];
    let mut model = GrayScott::pearson(SIDE, feed, kill)?;
    model.dx = 2.5 / 256.0;
    Ok(model)
}

/// A three-stop ramp over [0, 1] (clamped).
fn colour(s: f64) -> [u8; 4] {
    const STOPS: [[f64; 3]; 3] = [
        [8.0, 16.0, 48.0],
        [20.0, 140.0, 150.0],
        [250.0, 240.0, 170.0],
    ];
    let s = s.clamp(0.0, 1.0) * 2.0;
    let (k, f) = if s < 1.0 { (0, s) } else { (1, s - 1.0) };
    let mix = |c: usize| (STOPS[k][c] + f * (STOPS[k + 1][c] - STOPS[k][c])) as u8;
    [mix(0), mix(1), mix(2), 255]
}
