//! Particle systems: state sized at run time, forces written as per-element kernels, and the
//! sparse Jacobian assembled from the topology.
//!
//! A particle model has `#[position]` and `#[velocity]` fields of type `Vec<Vector3<f64>>` (or
//! `Vec<Vector2<f64>>`), a `#[mass]` field `Vec<f64>`, optionally a `#[pinned]` field `Vec<usize>`,
//! and forces written as kernels in its `#[system]` impl:
//!
//! - `#[pair(links)]` on `fn(&self, link: &L, xa, xb[, va, vb]) -> VectorD`: the force on particle
//!   `a` of each link in the field `links: Vec<L>` (`L:` [`Link`]); particle `b` gets its opposite
//!   (Newton's third law).
//! - `#[particle]` on `fn(&self[, i: usize], x[, v]) -> VectorD`: a force on every particle.
//!
//! `#[system]` differentiates each kernel into D×D blocks (∂f/∂xa, ∂f/∂xb, ∂f/∂va, ∂f/∂vb) and
//! implements [`ParticleSystem`]; the runtime sums the kernels into accelerations f/m for every
//! integrator, and into the sparse Newton matrix of implicit Euler ([`ParticleJacobian`]).
//!
//! Pinned particles keep their initial velocity (zero: fixed in place): their acceleration is
//! zero, whatever the forces on them.

pub(crate) mod glue;
mod jacobian;

use std::fmt;

use nalgebra::SVector;

use crate::{Error, Model, Result, State};

/// Renamed [`crate::LinearWork`], a section of [`crate::Stats`], at the crate root.
#[deprecated(
    since = "0.1.0",
    note = "renamed `odyn::LinearWork`; a run's is `trajectory.stats.linear`"
)]
pub type Factorizations = crate::LinearWork;
pub use jacobian::ParticleJacobian;

/// The state of a particle model: every position, then every velocity, as one `Vec<f64>`.
#[derive(PartialEq)]
pub struct ParticleState<const D: usize> {
    components: Vec<f64>,
    /// The model's position and velocity field names, for CSV headers and errors.
    names: [&'static str; 2],
}

impl<const D: usize> ParticleState<D> {
    /// A state with these positions and velocities, named `x` and `v`.
    ///
    /// Errors: [`Error::InvalidInput`] when the two lists differ in length.
    pub fn new(positions: &[SVector<f64, D>], velocities: &[SVector<f64, D>]) -> Result<Self> {
        if positions.len() != velocities.len() {
            return Err(Error::invalid(
                "particle state",
                format!(
                    "{} positions but {} velocities",
                    positions.len(),
                    velocities.len()
                ),
            ));
        }
        Ok(Self::from_fields(positions, velocities, ["x", "v"]))
    }

    /// The state of a model's fields; lengths are checked by [`Model::check`].
    pub(crate) fn from_fields(
        positions: &[SVector<f64, D>],
        velocities: &[SVector<f64, D>],
        names: [&'static str; 2],
    ) -> Self {
        let components = positions
            .iter()
            .chain(velocities)
            .flat_map(|p| p.iter().copied())
            .collect();
        ParticleState { components, names }
    }

    /// Number of particles.
    pub fn len(&self) -> usize {
        self.components.len() / (2 * D)
    }

    /// Whether there are no particles.
    pub fn is_empty(&self) -> bool {
        self.components.is_empty()
    }

    /// The positions.
    pub fn positions(&self) -> &[SVector<f64, D>] {
        vectors(self.components.split_at(self.components.len() / 2).0)
    }

    /// The velocities.
    pub fn velocities(&self) -> &[SVector<f64, D>] {
        vectors(self.components.split_at(self.components.len() / 2).1)
    }

    /// The positions, mutably.
    pub fn positions_mut(&mut self) -> &mut [SVector<f64, D>] {
        let half = self.components.len() / 2;
        vectors_mut(&mut self.components[..half])
    }

    /// The velocities, mutably.
    pub fn velocities_mut(&mut self) -> &mut [SVector<f64, D>] {
        let half = self.components.len() / 2;
        vectors_mut(&mut self.components[half..])
    }

    /// Positions and velocities, for reading one and writing the other.
    pub fn split_mut(&mut self) -> (&mut [SVector<f64, D>], &mut [SVector<f64, D>]) {
        let half = self.components.len() / 2;
        let (x, v) = self.components.split_at_mut(half);
        (vectors_mut(x), vectors_mut(v))
    }
}

impl<const D: usize> Clone for ParticleState<D> {
    fn clone(&self) -> Self {
        ParticleState {
            components: self.components.clone(),
            names: self.names,
        }
    }

    /// Reuses the buffer: the integrators copy states every step and must not allocate.
    fn clone_from(&mut self, source: &Self) {
        self.components.clone_from(&source.components);
        self.names = source.names;
    }
}

impl<const D: usize> fmt::Debug for ParticleState<D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("ParticleState")
            .field(self.names[0], &self.positions())
            .field(self.names[1], &self.velocities())
            .finish()
    }
}

impl<const D: usize> State for ParticleState<D> {
    #[inline(always)]
    fn as_slice(&self) -> &[f64] {
        &self.components
    }

    #[inline(always)]
    fn as_mut_slice(&mut self) -> &mut [f64] {
        &mut self.components
    }

    fn component_name(&self, index: usize) -> String {
        let half = self.components.len() / 2;
        let (name, i) = if index < half {
            (self.names[0], index)
        } else {
            (self.names[1], index - half)
        };
        const AXES: [&str; 4] = ["x", "y", "z", "w"];
        let axis = AXES.get(i % D).copied().unwrap_or("?");
        format!("{name}[{}].{axis}", i / D)
    }

    /// A copy whose components are reserved with `try_reserve_exact`.
    ///
    /// Errors: [`Error::InvalidInput`] (field `particle state`) giving the number of particles
    /// when the copy cannot be allocated.
    fn try_clone(&self) -> Result<Self> {
        let mut components = Vec::new();
        if components.try_reserve_exact(self.components.len()).is_err() {
            let what = format!("has {} particles in {D}-D", self.len());
            return Err(Error::copy_refused(
                "particle state",
                what,
                self.components.len(),
                "fewer particles",
            ));
        }
        components.extend_from_slice(&self.components);
        Ok(ParticleState {
            components,
            names: self.names,
        })
    }
}

/// `components` (a multiple of D long) as D-vectors, without copying.
#[inline(always)]
fn vectors<const D: usize>(components: &[f64]) -> &[SVector<f64, D>] {
    const { assert!(size_of::<SVector<f64, D>>() == D * size_of::<f64>()) };
    const { assert!(align_of::<SVector<f64, D>>() == align_of::<f64>()) };
    // SAFETY: `SVector<f64, D>` is `#[repr(C)]` over a `#[repr(transparent)]` `[[f64; D]; 1]`, so
    // it has the layout of `[f64; D]` (size and alignment asserted above); the length rounds down.
    unsafe {
        core::slice::from_raw_parts(
            components.as_ptr().cast::<SVector<f64, D>>(),
            components.len() / D,
        )
    }
}

/// Mutable [`vectors`].
#[inline(always)]
fn vectors_mut<const D: usize>(components: &mut [f64]) -> &mut [SVector<f64, D>] {
    const { assert!(size_of::<SVector<f64, D>>() == D * size_of::<f64>()) };
    // SAFETY: as in `vectors`; the borrow is unique.
    unsafe {
        core::slice::from_raw_parts_mut(
            components.as_mut_ptr().cast::<SVector<f64, D>>(),
            components.len() / D,
        )
    }
}

/// An element a pair kernel runs over: it joins two particles.
pub trait Link {
    /// The two particles, `[a, b]`; the kernel's force acts on `a`, its opposite on `b`.
    fn ends(&self) -> [usize; 2];

    /// Checks the link's own parameters (a spring's rest length, ...); the message says what is
    /// wrong.
    fn check(&self) -> std::result::Result<(), String> {
        Ok(())
    }
}

impl Link for [usize; 2] {
    fn ends(&self) -> [usize; 2] {
        *self
    }
}

/// A damped spring between particles `a` and `b`: the usual link of cloth and rope.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spring {
    /// First particle.
    pub a: usize,
    /// Second particle.
    pub b: usize,
    /// Rest length (> 0).
    pub rest: f64,
    /// Stiffness k (N/m, ≥ 0).
    pub stiffness: f64,
    /// Damping c along the spring (N·s/m, ≥ 0).
    pub damping: f64,
}

impl Spring {
    /// A spring between `a` and `b` at rest at their distance in `positions` (NaN rest length
    /// when either index is out of range, which [`Model::check`] then reports).
    pub fn at_rest<const D: usize>(
        positions: &[SVector<f64, D>],
        a: usize,
        b: usize,
        stiffness: f64,
        damping: f64,
    ) -> Spring {
        let rest = match (positions.get(a), positions.get(b)) {
            (Some(pa), Some(pb)) => (pb - pa).norm(),
            _ => f64::NAN,
        };
        Spring {
            a,
            b,
            rest,
            stiffness,
            damping,
        }
    }
}

impl Link for Spring {
    fn ends(&self) -> [usize; 2] {
        [self.a, self.b]
    }

    fn check(&self) -> std::result::Result<(), String> {
        if !(self.rest.is_finite() && self.rest > 0.0) {
            return Err(format!(
                "has rest length {}; it must be finite and positive",
                self.rest
            ));
        }
        if !(self.stiffness.is_finite() && self.stiffness >= 0.0) {
            return Err(format!(
                "has stiffness {}; it must be finite and non-negative",
                self.stiffness
            ));
        }
        if !(self.damping.is_finite() && self.damping >= 0.0) {
            return Err(format!(
                "has damping {}; it must be finite and non-negative",
                self.damping
            ));
        }
        Ok(())
    }
}

/// A list of links, seen through its ends: the topology a pair kernel contributes.
pub trait LinkList {
    /// Number of links.
    fn len(&self) -> usize;
    /// Whether there are none.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The ends of link `index`.
    fn ends(&self, index: usize) -> [usize; 2];
    /// [`Link::check`] of link `index`.
    fn check(&self, index: usize) -> std::result::Result<(), String>;
}

impl<L: Link> LinkList for Vec<L> {
    fn len(&self) -> usize {
        <[L]>::len(self)
    }
    fn ends(&self, index: usize) -> [usize; 2] {
        self[index].ends()
    }
    fn check(&self, index: usize) -> std::result::Result<(), String> {
        self[index].check()
    }
}

/// A particle model in D dimensions, implemented by `#[system]`: the kernels and the topology.
pub trait ParticleSystem<const D: usize>: Model<State = ParticleState<D>> {
    /// The mass of every particle.
    fn masses(&self) -> &[f64];

    /// The pinned particles.
    fn pinned(&self) -> &[usize];

    /// The fields that need one entry per particle and their lengths (positions, velocities,
    /// masses).
    fn per_particle(&self) -> [(&'static str, usize); 3];

    /// Every pair kernel's links with the field they come from, in kernel order.
    fn link_lists(&self) -> Vec<(&'static str, &dyn LinkList)>;

    /// Adds every kernel's force at (x, v) into `force`.
    fn add_forces(
        &self,
        t: f64,
        x: &[SVector<f64, D>],
        v: &[SVector<f64, D>],
        force: &mut [SVector<f64, D>],
    );

    /// Writes every kernel's derivative blocks at (x, v) into `jacobian`: the pair kernels' in
    /// link order, then the per-particle kernels' added on the diagonal.
    fn add_force_jacobian(
        &self,
        t: f64,
        x: &[SVector<f64, D>],
        v: &[SVector<f64, D>],
        jacobian: &mut ParticleJacobian<D>,
    );

    /// The model's `fn potential` at (x, v), if it defines one.
    #[doc(hidden)]
    fn potential_of(&self, x: &[SVector<f64, D>], v: &[SVector<f64, D>]) -> Option<f64>;

    /// The kinetic energy ½·Σ mᵢ|vᵢ|² of `state`.
    fn kinetic_energy(&self, state: &ParticleState<D>) -> f64 {
        let v = state.velocities();
        self.masses()
            .iter()
            .zip(v)
            .map(|(m, v)| 0.5 * m * v.norm_squared())
            .sum()
    }

    /// The potential energy of `state`, if the model defines `fn potential`.
    fn potential_energy(&self, state: &ParticleState<D>) -> Option<f64> {
        self.potential_of(state.positions(), state.velocities())
    }

    /// The net force on every particle at `state` and time `t`, pinned ones included (a pinned
    /// particle's is what holds it): for equilibrium checks.
    fn net_forces(&self, t: f64, state: &ParticleState<D>) -> Vec<SVector<f64, D>> {
        let mut force = vec![SVector::zeros(); state.len()];
        self.add_forces(t, state.positions(), state.velocities(), &mut force);
        force
    }
}
