//! What the code `#[system]` generates for a particle model calls: the kernels summed into
//! forces, and the `Model` and `Jacobian` methods of every particle model. Reached through
//! `odyn::__private::particles`; not a stable API.

use nalgebra::{SMatrix, SVector};

use super::{Link, ParticleJacobian, ParticleState, ParticleSystem};
use crate::{Error, Result, State};

/// Sums a pair kernel over `links`: the force on `a`, its opposite on `b`.
#[inline]
pub fn pair_forces<L: Link, const D: usize>(
    links: &[L],
    x: &[SVector<f64, D>],
    v: &[SVector<f64, D>],
    force: &mut [SVector<f64, D>],
    kernel: impl Fn(
        &L,
        &SVector<f64, D>,
        &SVector<f64, D>,
        &SVector<f64, D>,
        &SVector<f64, D>,
    ) -> SVector<f64, D>,
) {
    for link in links {
        let [a, b] = link.ends();
        let f = kernel(link, &x[a], &x[b], &v[a], &v[b]);
        force[a] += f;
        force[b] -= f;
    }
}

/// Sums a per-particle kernel over every particle.
#[inline]
pub fn particle_forces<const D: usize>(
    x: &[SVector<f64, D>],
    v: &[SVector<f64, D>],
    force: &mut [SVector<f64, D>],
    kernel: impl Fn(usize, &SVector<f64, D>, &SVector<f64, D>) -> SVector<f64, D>,
) {
    for (i, ((x, v), f)) in x.iter().zip(v).zip(force.iter_mut()).enumerate() {
        *f += kernel(i, x, v);
    }
}

/// Writes the accelerations f/m at `state` into `accel`, zero for pinned particles.
#[inline]
fn accelerations<M: ParticleSystem<D>, const D: usize>(
    model: &M,
    t: f64,
    state: &ParticleState<D>,
    accel: &mut [SVector<f64, D>],
) {
    accel.fill(SVector::zeros());
    model.add_forces(t, state.positions(), state.velocities(), accel);
    for (a, m) in accel.iter_mut().zip(model.masses()) {
        *a /= *m;
    }
    for &p in model.pinned() {
        accel[p] = SVector::zeros();
    }
}

/// [`Model::derivative`](crate::Model::derivative) of a particle model: (ẋ, v̇) = (v, f/m).
#[inline]
pub fn derivative<M: ParticleSystem<D>, const D: usize>(
    model: &M,
    t: f64,
    y: &ParticleState<D>,
    dydt: &mut ParticleState<D>,
) {
    let (dx, dv) = dydt.split_mut();
    dx.copy_from_slice(y.velocities());
    accelerations(model, t, y, dv);
}

/// [`crate::SecondOrder::acceleration`] of a particle model.
#[inline]
pub fn acceleration<M: ParticleSystem<D>, const D: usize>(
    model: &M,
    t: f64,
    state: &ParticleState<D>,
    accel: &mut ParticleState<D>,
) {
    accelerations(model, t, state, accel.velocities_mut());
}

/// [`Model::energy`](crate::Model::energy) of a particle model: kinetic plus potential, when it has a potential.
pub fn energy<M: ParticleSystem<D>, const D: usize>(
    model: &M,
    state: &ParticleState<D>,
) -> Option<f64> {
    model
        .potential_energy(state)
        .map(|potential| model.kinetic_energy(state) + potential)
}

/// [`crate::Jacobian::jacobian`] of a particle model.
#[inline]
pub fn jacobian<M: ParticleSystem<D>, const D: usize>(
    model: &M,
    t: f64,
    y: &ParticleState<D>,
    jacobian: &mut ParticleJacobian<D>,
) {
    jacobian.begin();
    model.add_force_jacobian(t, y.positions(), y.velocities(), jacobian);
}

/// [`crate::Jacobian::jacobian_matrix`] of a particle model.
pub fn jacobian_matrix<M: ParticleSystem<D>, const D: usize>(
    model: &M,
    state: &ParticleState<D>,
) -> ParticleJacobian<D> {
    ParticleJacobian::new(model, state.len())
}

/// [`Model::check`](crate::Model::check) of a particle model: one entry per particle everywhere, positive finite
/// masses, pinned particles and link ends in range, links between two different particles, and
/// each link's own [`Link::check`].
pub fn check<M: ParticleSystem<D>, const D: usize>(
    model: &M,
    state: &ParticleState<D>,
) -> Result<()> {
    let bad = |what: String, reason: String| Error::BadModel {
        model: M::NAME,
        what,
        reason,
    };
    let n = state.len();
    for (field, len) in model.per_particle() {
        if len != n {
            return Err(bad(
                format!("`{field}`"),
                format!("has {len} entries for {n} particles"),
            ));
        }
    }
    if state.as_slice().len() != 2 * D * n {
        return Err(bad(
            "the state".into(),
            "has positions and velocities of different lengths".into(),
        ));
    }
    for (i, &m) in model.masses().iter().enumerate() {
        if !(m.is_finite() && m > 0.0) {
            return Err(bad(
                format!("mass[{i}]"),
                format!("is {m}; every particle needs a finite positive mass"),
            ));
        }
    }
    for (k, &p) in model.pinned().iter().enumerate() {
        if p >= n {
            return Err(bad(
                format!("pinned[{k}]"),
                format!("is particle {p}, but there are only {n} particles"),
            ));
        }
    }
    for (field, links) in model.link_lists() {
        for k in 0..links.len() {
            let [a, b] = links.ends(k);
            let what = || format!("{field}[{k}]");
            if a >= n || b >= n {
                return Err(bad(
                    what(),
                    format!("joins particles {a} and {b}, but there are only {n} particles"),
                ));
            }
            if a == b {
                return Err(bad(what(), format!("joins particle {a} to itself")));
            }
            links.check(k).map_err(|reason| bad(what(), reason))?;
        }
    }
    Ok(())
}

/// [`Model::state`](crate::Model::state) of a particle model: its position and velocity fields,
/// named `names`.
#[inline]
pub fn state<const D: usize>(
    positions: &[SVector<f64, D>],
    velocities: &[SVector<f64, D>],
    names: [&'static str; 2],
) -> ParticleState<D> {
    ParticleState::from_fields(positions, velocities, names)
}

/// Writes the derivative blocks of a pair kernel over `links` (the next links in kernel order)
/// into `jacobian`:
/// `kernel(link, xa, xb, va, vb)` returns ∂fₐ/∂xₐ, ∂fₐ/∂x_b, ∂fₐ/∂vₐ, ∂fₐ/∂v_b.
#[inline]
#[allow(
    clippy::type_complexity,
    reason = "the kernel's signature is the pair kernel's own"
)]
pub fn pair_blocks<L: Link, const D: usize>(
    jacobian: &mut ParticleJacobian<D>,
    links: &[L],
    x: &[SVector<f64, D>],
    v: &[SVector<f64, D>],
    kernel: impl Fn(
        &L,
        &SVector<f64, D>,
        &SVector<f64, D>,
        &SVector<f64, D>,
        &SVector<f64, D>,
    ) -> [SMatrix<f64, D, D>; 4],
) {
    let start = jacobian.cursor;
    let blocks = &mut jacobian.pairs[start..start + links.len()];
    for (link, out) in links.iter().zip(blocks) {
        let [a, b] = link.ends();
        *out = kernel(link, &x[a], &x[b], &v[a], &v[b]);
    }
    jacobian.cursor += links.len();
}

/// Adds the derivative blocks of a per-particle kernel to `jacobian`: `kernel(i, x, v)` returns
/// ∂fᵢ/∂xᵢ, ∂fᵢ/∂vᵢ.
#[inline]
pub fn particle_blocks<const D: usize>(
    jacobian: &mut ParticleJacobian<D>,
    x: &[SVector<f64, D>],
    v: &[SVector<f64, D>],
    kernel: impl Fn(usize, &SVector<f64, D>, &SVector<f64, D>) -> [SMatrix<f64, D, D>; 2],
) {
    for (i, ((x, v), out)) in x.iter().zip(v).zip(&mut jacobian.diagonal).enumerate() {
        let [dx, dv] = kernel(i, x, v);
        out[0] += dx;
        out[1] += dv;
    }
}
