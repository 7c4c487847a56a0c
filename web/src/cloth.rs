//! One cloth twice: XPBD (rigid-ish distance constraints, substeps) beside the spring cloth on
//! implicit Euler, both at dt = 1/60 s, both dragged by the same hand. Implicit Euler's step is
//! solved the Baraff–Witkin way (one Newton step, one sparse Cholesky a step) or by the
//! quasi-Newton solve (L-BFGS on a link Laplacian factorized once a run).

use odyn::integrators::ImplicitEuler;
use odyn::nalgebra::Vector3;
use odyn::xpbd::Xpbd;
use odyn::{
    Fingerprint, FixedTimestep, Method, Model, NewtonOptions, ParticleSolve, QuasiNewtonOptions,
    State, Stepper,
};
use scenes::{Cloth, Sheet};
use wasm_bindgen::prelude::*;

use crate::{Js, hex, js};

/// Particles a side: 256 particles, 768 unknowns for implicit Euler's Newton.
pub(crate) const SIDE: usize = 16;

/// The step: one 60 Hz frame.
const DT: f64 = 1.0 / 60.0;

/// XPBD substeps a step (one constraint sweep each).
const SUBSTEPS: u32 = 20;

/// Steps in [`ClothLab::check`]: the free corner dragged for the first second, then let go.
const CHECK_STEPS: u32 = 120;

/// The oblique view: screen = (x + 0.4·z, y + 0.25·z), y up; the sheet starts level in the
/// x–z plane and falls towards −y.
const VIEW: [f64; 2] = [0.4, 0.25];

/// How implicit Euler's step is solved.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Solve {
    /// As Baraff & Witkin take it ("Large Steps in Cloth Simulation", 1998, §3): one Newton
    /// iteration a step on the spring Jacobian made positive definite, so one sparse Cholesky
    /// factorization a step (full Newton on the falling sheet takes ~8).
    BaraffWitkin,
    /// The quasi-Newton solve at its defaults (Liu, Bouaziz & Kavan 2017): one factorization of
    /// the link Laplacian a run and 8 L-BFGS iterations a step.
    QuasiNewton,
}

impl Solve {
    const ALL: [Solve; 2] = [Solve::BaraffWitkin, Solve::QuasiNewton];

    /// Its name on the page.
    fn name(self) -> &'static str {
        match self {
            Solve::BaraffWitkin => "baraff_witkin",
            Solve::QuasiNewton => "quasi_newton",
        }
    }

    fn label(self) -> &'static str {
        match self {
            Solve::BaraffWitkin => "one Newton step (Baraff–Witkin)",
            Solve::QuasiNewton => "quasi-Newton (L-BFGS, 8 iterations)",
        }
    }

    fn newton(self) -> NewtonOptions {
        match self {
            Solve::BaraffWitkin => NewtonOptions {
                linearized: true,
                definite: true,
                ..NewtonOptions::default()
            },
            Solve::QuasiNewton => NewtonOptions {
                particle_solve: ParticleSolve::QuasiNewton(QuasiNewtonOptions::default()),
                ..NewtonOptions::default()
            },
        }
    }
}

/// The cloth panel.
#[wasm_bindgen]
pub struct ClothLab {
    model: &'static Cloth,
    solve: Solve,
    structural: Vec<usize>,
    implicit: Stepper<'static, Cloth, ImplicitEuler<Cloth>>,
    xpbd: Xpbd<3>,
    clock: FixedTimestep,
    /// The dragged particle and where on the screen it is held.
    grabbed: Option<(usize, [f64; 2])>,
}

impl ClothLab {
    /// Where the grabbed particle is held: its screen point at its own depth `z`.
    fn held_at(&self, z: f64) -> Option<(usize, Vector3<f64>)> {
        let (i, [sx, sy]) = self.grabbed?;
        Some((i, Vector3::new(sx - VIEW[0] * z, sy - VIEW[1] * z, z)))
    }

    /// Puts implicit Euler's grabbed particle where it is held, at rest. The model's pinned
    /// particles are fixed when its stepper is made, so a dragged one is put back before and
    /// after every step (its springs move it during the step, their neighbours follow it).
    fn place_implicit(&mut self) {
        let z = self
            .grabbed
            .map(|(i, _)| self.implicit.state().positions()[i].z);
        if let Some((i, at)) = z.and_then(|z| self.held_at(z)) {
            let (x, v) = self.implicit.state_mut().split_mut();
            x[i] = at;
            v[i] = Vector3::zeros();
        }
    }

    /// One step of both. XPBD holds the grabbed particle through the step as if pinned.
    fn step(&mut self) -> odyn::Result<()> {
        if let Some((i, at)) = self
            .grabbed
            .and_then(|(i, _)| self.held_at(self.xpbd.x[i].z))
        {
            self.xpbd.hold(i, Some(at))?;
        }
        self.place_implicit();
        self.implicit.step()?;
        self.place_implicit();
        self.xpbd.step(DT)
    }
}

#[wasm_bindgen]
impl ClothLab {
    /// The `cloth` example's sheet at 16², springs damped at 0.02 N·s/m, level and about to
    /// fall from its two pinned corners.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Js<ClothLab> {
        let (cloth, structural) = Sheet {
            damping: 0.02,
            ..Sheet::falling(SIDE)
        }
        .build();
        let model: &'static Cloth = Box::leak(Box::new(cloth));
        Ok(ClothLab {
            model,
            structural,
            solve: Solve::BaraffWitkin,
            implicit: js(implicit(model, Solve::BaraffWitkin))?,
            xpbd: js(model.as_xpbd(SUBSTEPS))?,
            clock: FixedTimestep::new(),
            grabbed: None,
        })
    }

    /// The names of implicit Euler's solves, for [`ClothLab::set_solve`].
    pub fn solves() -> Vec<String> {
        Solve::ALL.map(|s| s.name().to_owned()).to_vec()
    }

    /// Their labels.
    pub fn solve_labels() -> Vec<String> {
        Solve::ALL.map(|s| s.label().to_owned()).to_vec()
    }

    /// Solves implicit Euler's steps by `name` (one of [`ClothLab::solves`]) from the level
    /// sheet again.
    pub fn set_solve(&mut self, name: &str) -> Js<()> {
        self.solve = Solve::ALL
            .into_iter()
            .find(|s| s.name() == name)
            .ok_or_else(|| format!("no solve named {name:?}: one of {:?}", Self::solves()))?;
        self.restart()
    }

    /// Back to the level sheet.
    pub fn restart(&mut self) -> Js<()> {
        self.implicit = js(implicit(self.model, self.solve))?;
        self.xpbd = js(self.model.as_xpbd(SUBSTEPS))?;
        self.clock = FixedTimestep::new();
        self.grabbed = None;
        Ok(())
    }

    /// Advances both by one display frame of `seconds` (real time). Returns the steps taken.
    pub fn frame(&mut self, seconds: f64) -> Js<u32> {
        let mut clock = std::mem::take(&mut self.clock);
        let tick = clock.advance_with(seconds, DT, || self.step());
        self.clock = clock;
        Ok(js(tick)?.steps as u32)
    }

    /// Grabs the particle of the implicit cloth nearest the screen point (`sx`, `sy`), if one is
    /// within `radius`; both cloths' particle of that index follow [`ClothLab::drag`].
    pub fn grab(&mut self, sx: f64, sy: f64, radius: f64) -> bool {
        self.release();
        let points = project(self.implicit.state().positions());
        let nearest = points
            .chunks_exact(2)
            .map(|p| (p[0] - sx).powi(2) + (p[1] - sy).powi(2))
            .enumerate()
            .filter(|&(i, _)| !self.model.pinned.contains(&i))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        self.grabbed = nearest
            .filter(|&(_, d2)| d2 <= radius * radius)
            .map(|(i, _)| (i, [sx, sy]));
        self.grabbed.is_some()
    }

    /// Moves the grabbed particle's screen point.
    pub fn drag(&mut self, sx: f64, sy: f64) {
        if let Some((_, point)) = &mut self.grabbed {
            *point = [sx, sy];
        }
    }

    /// Lets go.
    pub fn release(&mut self) {
        if let Some((i, _)) = self.grabbed.take() {
            // `i` is one of the cloth's particles: letting it go cannot fail.
            let _ = self.xpbd.hold(i, None);
        }
    }

    /// Two seconds: the free corner dragged along a fixed path for the first, then let go.
    pub fn check(&mut self) -> Js<u32> {
        self.restart()?;
        let corner = SIDE * SIDE - 1;
        for step in 0..CHECK_STEPS {
            if step < CHECK_STEPS / 2 {
                let s = f64::from(step);
                self.grabbed = Some((corner, [1.4 - 0.01 * s, 0.25 - 0.015 * s]));
            } else if step == CHECK_STEPS / 2 {
                self.release();
            }
            js(self.step())?;
        }
        Ok(CHECK_STEPS)
    }

    /// Both cloths' time, positions and velocities, as sixteen hex digits.
    pub fn fingerprint(&self) -> String {
        let mut hash = Fingerprint::new();
        hash.add(self.implicit.t());
        hash.extend(self.implicit.state().as_slice());
        for (x, v) in self.xpbd.x.iter().zip(&self.xpbd.v) {
            hash.extend(x.iter().chain(v.iter()));
        }
        hex(hash.finish())
    }

    /// The methods' labels.
    pub fn method(&self) -> String {
        format!(
            "XPBD ({SUBSTEPS} substeps) | {}, {}",
            Method::ImplicitEuler.info().label,
            self.solve.label()
        )
    }

    /// The step.
    pub fn dt(&self) -> f64 {
        DT
    }

    /// Time.
    pub fn t(&self) -> f64 {
        self.implicit.t()
    }

    /// Particles a side.
    pub fn side(&self) -> usize {
        SIDE
    }

    /// The XPBD cloth's particles on the screen (x, y pairs, metres, y up), then the implicit
    /// cloth's.
    pub fn points(&self) -> Vec<f64> {
        let mut points = project(&self.xpbd.x);
        points.extend(project(self.implicit.state().positions()));
        points
    }

    /// The structural springs' ends, two particle indices each.
    pub fn links(&self) -> Vec<u32> {
        self.structural
            .iter()
            .flat_map(|&s| {
                [
                    self.model.springs[s].a as u32,
                    self.model.springs[s].b as u32,
                ]
            })
            .collect()
    }

    /// Implicit Euler's factorizations so far: one a step (Baraff–Witkin), or one a run
    /// (quasi-Newton).
    pub fn factorizations(&self) -> f64 {
        self.implicit.stats().factorizations as f64
    }
}

/// Implicit Euler on the cloth, its steps solved by `solve`.
fn implicit(
    model: &'static Cloth,
    solve: Solve,
) -> odyn::Result<Stepper<'static, Cloth, ImplicitEuler<Cloth>>> {
    Stepper::with_newton(model, model.state(), 0.0, DT, &solve.newton())
}

/// Screen coordinates of `x` in the oblique view.
fn project(x: &[Vector3<f64>]) -> Vec<f64> {
    x.iter()
        .flat_map(|p| [p.x + VIEW[0] * p.z, p.y + VIEW[1] * p.z])
        .collect()
}
