//! Extended position-based dynamics (XPBD): particles held by constraints instead of forces.
//!
//! A force-based particle model (`#[system]` with kernels) is an ODE whose stiffness the
//! integrator must survive; XPBD instead moves the particles, then projects their positions onto
//! the constraints, then derives the velocities from the motion. Each constraint C(x) = 0 has a
//! compliance α (the inverse of a stiffness: α = 0 is rigid), and its Lagrange multiplier λ is
//! accumulated over the iterations of a substep:
//!
//! Δλ = (−C − α̃·λ) / (Σᵢ wᵢ·|∇ᵢC|² + α̃),   xᵢ += wᵢ·∇ᵢC·Δλ,   α̃ = α/h²,
//!
//! with wᵢ = 1/mᵢ (0 for a pinned particle). Because the compliance term enters the update, the
//! converged positions satisfy C = −α·λ — the constraint behaves as a spring of stiffness 1/α
//! whatever the number of iterations and the step (Macklin, Müller & Chentanez, "XPBD:
//! Position-Based Simulation of Compliant Constrained Dynamics", MIG 2016, eq. (18)). A step of
//! size Δt is split into `substeps` substeps of one or a few iterations each, which converges far
//! faster than many iterations of one big step (Macklin, Storey, Lu, Terdiman, Chentanez, Jeschke
//! & Müller, "Small Steps in Physics Simulation", SCA 2019).
//!
//! # How it fits beside the ODE models
//!
//! XPBD is not an integrator of y′ = f(t, y): it never evaluates forces (other than gravity) and
//! needs no Jacobian. It takes the topology of a particle model — positions, velocities, masses,
//! pinned particles, links — as [`Xpbd::new`]'s input, and its constraints are fixed for the
//! run, like a particle model's links. Collisions with the colliders are resolved at every
//! iteration as inequality constraints.

mod check;
mod constraints;

use nalgebra::SVector;

use crate::{Error, Result};

pub use constraints::{Collider, Constraint};

/// Substeps and iterations: plain data with a [`Default`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct XpbdOptions {
    /// Substeps per step, 1 to [`XpbdOptions::MAX`]; default 10 (Small Steps: many substeps of
    /// one iteration each converge fastest).
    pub substeps: u32,
    /// Constraint sweeps per substep, 1 to [`XpbdOptions::MAX`]; default 1.
    pub iterations: u32,
}

impl XpbdOptions {
    /// The most substeps, and the most iterations, a step may take: 10 000 (a million sweeps
    /// of the constraints per step at both bounds). Far beyond what converges (Small Steps uses
    /// tens), and it keeps a mistyped `u32::MAX` from running for hours.
    pub const MAX: u32 = 10_000;
}

impl Default for XpbdOptions {
    fn default() -> Self {
        XpbdOptions {
            substeps: 10,
            iterations: 1,
        }
    }
}

/// Particles under gravity, held by [`Constraint`]s and kept out of [`Collider`]s.
#[derive(Clone, Debug)]
pub struct Xpbd<const D: usize> {
    /// Positions.
    pub x: Vec<SVector<f64, D>>,
    /// Velocities.
    pub v: Vec<SVector<f64, D>>,
    /// Inverse masses (0 for pinned and held particles).
    inverse_mass: Vec<f64>,
    /// Inverse masses as built (0 for pinned particles): what a held particle gets back.
    own_inverse_mass: Vec<f64>,
    /// The constraints, solved in this order.
    pub constraints: Vec<Constraint<D>>,
    /// The obstacles.
    pub colliders: Vec<Collider<D>>,
    /// Gravitational acceleration.
    pub gravity: SVector<f64, D>,
    /// Substeps and iterations.
    pub options: XpbdOptions,
    /// λ of each constraint over the current substep.
    lambda: Vec<f64>,
    previous: Vec<SVector<f64, D>>,
    /// Steps taken and the time they covered, to name the step that fails.
    steps: u64,
    t: f64,
}

impl<const D: usize> Xpbd<D> {
    /// Particles at `x` with velocities `v` and masses `mass`, the ones in `pinned` fixed in
    /// place (infinite mass), under `gravity`; no constraints or colliders yet (push them onto
    /// the public lists) and the default [`XpbdOptions`].
    ///
    /// Errors: [`Error::InvalidInput`] for lists of different lengths, a non-finite position,
    /// velocity or gravity, a mass that is not finite and positive, or a pinned particle that
    /// does not exist.
    pub fn new(
        x: Vec<SVector<f64, D>>,
        v: Vec<SVector<f64, D>>,
        mass: &[f64],
        pinned: &[usize],
        gravity: SVector<f64, D>,
    ) -> Result<Xpbd<D>> {
        let n = x.len();
        if v.len() != n || mass.len() != n {
            return Err(Error::invalid(
                "particles",
                format!(
                    "{n} positions, {} velocities, {} masses",
                    v.len(),
                    mass.len()
                ),
            ));
        }
        if let Some(i) = x
            .iter()
            .chain(&v)
            .position(|p| !p.iter().all(|c| c.is_finite()))
        {
            return Err(Error::invalid(
                "particles",
                format!(
                    "particle {} has a position or velocity that is not finite",
                    i % n
                ),
            ));
        }
        if let Some((i, m)) = mass
            .iter()
            .enumerate()
            .find(|(_, m)| !(m.is_finite() && **m > 0.0))
        {
            return Err(Error::invalid(
                "mass",
                format!("particle {i}: must be finite and positive, got {m:?}"),
            ));
        }
        if !gravity.iter().all(|c| c.is_finite()) {
            return Err(Error::invalid("gravity", "must be finite"));
        }
        let mut inverse_mass: Vec<f64> = mass.iter().map(|m| 1.0 / m).collect();
        for &p in pinned {
            if p >= n {
                return Err(Error::invalid(
                    "pinned",
                    format!("particle {p} does not exist ({n} particles)"),
                ));
            }
            inverse_mass[p] = 0.0;
        }
        Ok(Xpbd {
            previous: x.clone(),
            x,
            v,
            own_inverse_mass: inverse_mass.clone(),
            inverse_mass,
            constraints: Vec::new(),
            colliders: Vec::new(),
            gravity,
            options: XpbdOptions::default(),
            lambda: Vec::new(),
            steps: 0,
            t: 0.0,
        })
    }

    /// Advances by `dt` in `options.substeps` substeps.
    ///
    /// Errors, before the step: [`Error::InvalidInput`] for a `dt` that is not finite and
    /// positive, a substep h = dt/substeps so short that 1/h² overflows (dt below
    /// substeps·1.5e-154), a compliance α whose α/h² overflows (`constraints[k]`), or what
    /// [`Xpbd::check`] finds. After it: [`Error::NotFinite`] when the step left a position or
    /// velocity NaN or infinite (a step too large for gravity, a rest length or pin too far
    /// away); the state is then that of the failed step.
    pub fn step(&mut self, dt: f64) -> Result<()> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(Error::invalid(
                "dt",
                format!("must be finite and positive, got {dt:?}"),
            ));
        }
        self.check()?;
        let substeps = f64::from(self.options.substeps);
        let h = dt / substeps;
        // α̃ = α/h²: past 1/h² = f64::MAX even a rigid link (α = 0) would give 0·∞ = NaN.
        let inv_h2 = 1.0 / (h * h);
        if !inv_h2.is_finite() {
            // 2⁻⁵¹¹: the shortest substep whose 1/h² = 2¹⁰²² is finite.
            let shortest = substeps * 2f64.powi(-511);
            return Err(Error::invalid(
                "dt",
                format!(
                    "must be at least {shortest:e} with {substeps} substeps (the solver divides \
                     compliances by the substep squared), got {dt:?}"
                ),
            ));
        }
        if let Some((k, alpha)) = self
            .constraints
            .iter()
            .map(Constraint::compliance)
            .enumerate()
            .find(|(_, alpha)| !(alpha * inv_h2).is_finite())
        {
            return Err(Error::invalid(
                format!("constraints[{k}]"),
                format!(
                    "compliance {alpha:?} divided by the substep squared ({h:e} s)² overflows; \
                     lower it below {:e} (so soft a link holds nothing) or take longer steps",
                    f64::MAX / inv_h2
                ),
            ));
        }
        self.lambda.resize(self.constraints.len(), 0.0);
        for _ in 0..self.options.substeps {
            self.previous.clone_from(&self.x);
            for ((x, v), &w) in self.x.iter_mut().zip(&mut self.v).zip(&self.inverse_mass) {
                if w > 0.0 {
                    *v += h * self.gravity;
                    *x += h * *v;
                }
            }
            self.lambda.fill(0.0);
            for _ in 0..self.options.iterations {
                self.solve_constraints(h);
                self.collide();
            }
            for ((v, x), p) in self.v.iter_mut().zip(&self.x).zip(&self.previous) {
                *v = (x - p) / h;
            }
        }
        self.steps += 1;
        self.t += dt;
        self.check_finite(dt)
    }

    /// Holds particle `i` at `at`, at rest, through the steps that follow, as if pinned (a
    /// user's drag: call it again each frame with where the hand is); `None` lets it go, with
    /// its own mass again. A pinned particle stays pinned when let go.
    ///
    /// Errors: [`Error::InvalidInput`] for a particle that does not exist or a position that is
    /// not finite.
    pub fn hold(&mut self, i: usize, at: Option<SVector<f64, D>>) -> Result<()> {
        let n = self.x.len();
        if i >= n {
            return Err(Error::invalid(
                "particle",
                format!("particle {i} does not exist ({n} particles)"),
            ));
        }
        match at {
            Some(at) if !at.iter().all(|c| c.is_finite()) => Err(Error::invalid(
                "at",
                format!("particle {i} would be held at a position that is not finite"),
            )),
            Some(at) => {
                self.x[i] = at;
                self.v[i] = SVector::zeros();
                self.inverse_mass[i] = 0.0;
                Ok(())
            }
            None => {
                self.inverse_mass[i] = self.own_inverse_mass[i];
                Ok(())
            }
        }
    }

    /// The largest relative stretch |length/rest − 1| over the distance constraints.
    pub fn max_stretch(&self) -> f64 {
        self.constraints
            .iter()
            .filter_map(|c| match *c {
                Constraint::Distance {
                    ends: [a, b], rest, ..
                } if rest > 0.0 => Some(((self.x[b] - self.x[a]).norm() / rest - 1.0).abs()),
                _ => None,
            })
            .fold(0.0, f64::max)
    }
}
