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

use nalgebra::SVector;

use crate::{Error, Result};

/// One constraint between particles.
#[derive(Clone, Debug, PartialEq)]
pub enum Constraint<const D: usize> {
    /// |x_b − x_a| = `rest`, with compliance `compliance` (m/N; 0 is inextensible).
    Distance {
        /// The two particles.
        ends: [usize; 2],
        /// Rest length.
        rest: f64,
        /// Compliance α = 1/stiffness.
        compliance: f64,
    },
    /// Bending resistance along a chain or a sheet: the distance between the two outer
    /// particles of a triple (a, middle, c) is held at `rest` with compliance `compliance`, the
    /// "skip-one" bending constraint of position-based cloth and ropes (Müller, Heidelberger,
    /// Hennix & Ratcliff, "Position Based Dynamics", VRIPHYS 2006, §4.2 discusses it against
    /// the dihedral form). The middle particle is named so a model's lists read naturally; it
    /// takes no part.
    Bending {
        /// (a, middle, c).
        particles: [usize; 3],
        /// Rest distance between a and c.
        rest: f64,
        /// Compliance α.
        compliance: f64,
    },
    /// Particle `particle` is held at `at` (a rigid attachment that can be moved between steps).
    Pin {
        /// The particle.
        particle: usize,
        /// Where it is held.
        at: SVector<f64, D>,
    },
}

/// A static obstacle the particles cannot enter.
#[derive(Clone, Debug, PartialEq)]
pub enum Collider<const D: usize> {
    /// The half-space n·x ≥ offset (n a unit normal): e.g. the ground y ≥ 0.
    Plane {
        /// Unit normal pointing out of the obstacle.
        normal: SVector<f64, D>,
        /// n·x on the surface.
        offset: f64,
    },
    /// A solid sphere (a disc in 2-D). A particle inside is moved to the nearest point of the
    /// surface; one exactly at the centre, which has no nearest point, is moved out towards
    /// where it was at the start of the substep, or along +y (+x in 1-D) if that was the centre
    /// too.
    Sphere {
        /// Centre.
        centre: SVector<f64, D>,
        /// Radius.
        radius: f64,
    },
}

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
    /// Inverse masses (0 for pinned particles).
    inverse_mass: Vec<f64>,
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

    /// Checks the particles, constraints, colliders and options ([`Xpbd::step`] does, every
    /// step).
    ///
    /// Errors: [`Error::InvalidInput`] for position or velocity lists whose length changed, a
    /// position or velocity that is not finite (`x[i]`, `v[i]`), a non-finite gravity, a
    /// constraint on a particle that does not exist, a negative or non-finite compliance or
    /// rest length, a non-finite pin position, a plane whose normal is not a unit vector, a
    /// sphere with a non-positive radius, or substeps or iterations outside 1 to
    /// [`XpbdOptions::MAX`].
    pub fn check(&self) -> Result<()> {
        let n = self.inverse_mass.len();
        if self.x.len() != n || self.v.len() != n {
            return Err(Error::invalid(
                "particles",
                format!(
                    "{} positions and {} velocities for {n} particles; particles cannot be added \
                     or removed",
                    self.x.len(),
                    self.v.len()
                ),
            ));
        }
        for (name, list) in [("x", &self.x), ("v", &self.v)] {
            if let Some(i) = list.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
                return Err(Error::invalid(
                    format!("{name}[{i}]"),
                    format!(
                        "{:?} is not finite; write only finite values into `Xpbd::{name}`",
                        list[i].as_slice()
                    ),
                ));
            }
        }
        if !self.gravity.iter().all(|c| c.is_finite()) {
            return Err(Error::invalid(
                "gravity",
                format!("{:?} is not finite", self.gravity.as_slice()),
            ));
        }
        let exists = |i: usize, what: &str| {
            if i < n {
                Ok(())
            } else {
                Err(Error::invalid(
                    what.to_string(),
                    format!("particle {i} does not exist ({n} particles)"),
                ))
            }
        };
        let valid = |x: f64| x.is_finite() && x >= 0.0;
        for (k, c) in self.constraints.iter().enumerate() {
            let what = format!("constraints[{k}]");
            let (particles, rest, compliance): (&[usize], f64, f64) = match c {
                Constraint::Distance {
                    ends,
                    rest,
                    compliance,
                } => (ends, *rest, *compliance),
                Constraint::Bending {
                    particles,
                    rest,
                    compliance,
                } => (particles, *rest, *compliance),
                Constraint::Pin { particle, at } => {
                    if !at.iter().all(|c| c.is_finite()) {
                        return Err(Error::invalid(what, "the pin position must be finite"));
                    }
                    (std::slice::from_ref(particle), 0.0, 0.0)
                }
            };
            particles.iter().try_for_each(|&i| exists(i, &what))?;
            if !(valid(rest) && valid(compliance)) {
                return Err(Error::invalid(
                    what,
                    format!(
                        "rest length and compliance must be finite and ≥ 0, got {rest:?} and \
                         {compliance:?}"
                    ),
                ));
            }
        }
        for (k, c) in self.colliders.iter().enumerate() {
            let ok = match c {
                Collider::Plane { normal, offset } => {
                    (normal.norm() - 1.0).abs() < 1e-9 && offset.is_finite()
                }
                Collider::Sphere { centre, radius } => {
                    centre.iter().all(|c| c.is_finite()) && radius.is_finite() && *radius > 0.0
                }
            };
            if !ok {
                return Err(Error::invalid(
                    format!("colliders[{k}]"),
                    "a plane needs a unit normal and a finite offset; a sphere a finite centre \
                     and a positive radius",
                ));
            }
        }
        let XpbdOptions {
            substeps,
            iterations,
        } = self.options;
        let allowed = 1..=XpbdOptions::MAX;
        if !(allowed.contains(&substeps) && allowed.contains(&iterations)) {
            return Err(Error::invalid(
                "options",
                format!(
                    "substeps and iterations must be at least 1 and at most {}, got {substeps} \
                     and {iterations}",
                    XpbdOptions::MAX
                ),
            ));
        }
        Ok(())
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

    /// [`Error::NotFinite`] if the step just taken left a position or velocity non-finite.
    fn check_finite(&self, dt: f64) -> Result<()> {
        for (name, list) in [("x", &self.x), ("v", &self.v)] {
            if let Some((i, value)) = list
                .iter()
                .enumerate()
                .find_map(|(i, p)| p.iter().find(|c| !c.is_finite()).map(|c| (i, *c)))
            {
                return Err(Error::NotFinite {
                    solver: "Xpbd",
                    step: self.steps,
                    t: self.t,
                    dt,
                    component: format!("{name}[{i}]"),
                    value,
                    advice: "reduce dt, or check that rest lengths, pin positions and \
                             gravity are of the scene's size",
                });
            }
        }
        Ok(())
    }

    /// One Gauss–Seidel sweep over the constraints.
    fn solve_constraints(&mut self, h: f64) {
        let inv_h2 = 1.0 / (h * h);
        for (k, constraint) in self.constraints.iter().enumerate() {
            let (a, b, rest, compliance) = match *constraint {
                Constraint::Distance {
                    ends: [a, b],
                    rest,
                    compliance,
                } => (a, b, rest, compliance),
                Constraint::Bending {
                    particles: [a, _, c],
                    rest,
                    compliance,
                } => (a, c, rest, compliance),
                Constraint::Pin { particle, at } => {
                    self.x[particle] = at;
                    continue;
                }
            };
            let (wa, wb) = (self.inverse_mass[a], self.inverse_mass[b]);
            let d = self.x[b] - self.x[a];
            let length = d.norm();
            if wa + wb == 0.0 || length == 0.0 {
                continue;
            }
            let n = d / length;
            let c = length - rest;
            let alpha = compliance * inv_h2;
            let delta = (-c - alpha * self.lambda[k]) / (wa + wb + alpha);
            self.lambda[k] += delta;
            self.x[a] -= wa * delta * n;
            self.x[b] += wb * delta * n;
        }
    }

    /// Moves every particle inside a collider to its surface.
    fn collide(&mut self) {
        for ((x, &w), previous) in self
            .x
            .iter_mut()
            .zip(&self.inverse_mass)
            .zip(&self.previous)
        {
            if w == 0.0 {
                continue;
            }
            for collider in &self.colliders {
                match collider {
                    Collider::Plane { normal, offset } => {
                        let depth = offset - normal.dot(x);
                        if depth > 0.0 {
                            *x += depth * normal;
                        }
                    }
                    Collider::Sphere { centre, radius } => {
                        let d = *x - centre;
                        let distance = d.norm();
                        if distance < *radius {
                            *x = centre + *radius * outwards(d, distance, previous - centre);
                        }
                    }
                }
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

impl<const D: usize> Constraint<D> {
    /// The compliance α (0 for a pin, which is rigid).
    fn compliance(&self) -> f64 {
        match *self {
            Constraint::Distance { compliance, .. } | Constraint::Bending { compliance, .. } => {
                compliance
            }
            Constraint::Pin { .. } => 0.0,
        }
    }
}

/// The unit vector from a sphere's centre through a particle inside it at offset `d`
/// (|d| = `distance`). At the centre no direction is nearest the surface, so it is the one
/// towards `before`, the particle's offset at the start of the substep, and +y (+x in 1-D)
/// when that is zero too.
fn outwards<const D: usize>(
    d: SVector<f64, D>,
    distance: f64,
    before: SVector<f64, D>,
) -> SVector<f64, D> {
    if distance > 0.0 {
        return d / distance;
    }
    let norm = before.norm();
    if norm > 0.0 {
        return before / norm;
    }
    let mut up = SVector::zeros();
    if D > 0 {
        up[D.min(2) - 1] = 1.0;
    }
    up
}
