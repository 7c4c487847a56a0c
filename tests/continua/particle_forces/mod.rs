//! Implicit Euler on particle models beyond springs: the default (`ParticleSolve::Auto`, full
//! Newton) against theory on forces that are not springs — attraction, repulsion, a magnetic
//! force, softened gravity, damping — where it never gains energy and damps linear forces by
//! implicit Euler's factor; the one-step (Baraff–Witkin) form's energy gain that keeps it from
//! being the default; extreme stiffnesses, masses and steps; non-finite input and topology edge
//! cases as typed errors.

use odyn::integrators::ImplicitEuler;
use odyn::nalgebra::{Vector2, Vector3};
use odyn::particles::{ParticleState, Spring};
use odyn::prelude::*;
use odyn::{Error, Jacobian, Model, NewtonOptions, ParticleSolve, Stepper};
use scenes::Sheet;

mod extremes;
mod forces;
mod options;

/// The default: `ParticleSolve::Auto`.
fn auto() -> NewtonOptions {
    NewtonOptions::default()
}

/// Full Newton, named.
fn full() -> NewtonOptions {
    NewtonOptions {
        particle_solve: ParticleSolve::Newton,
        ..NewtonOptions::default()
    }
}

/// The Baraff–Witkin step set by hand, with `ParticleSolve::Newton` so `Auto` plays no part.
fn by_hand() -> NewtonOptions {
    NewtonOptions {
        linearized: true,
        definite: true,
        particle_solve: ParticleSolve::Newton,
        ..NewtonOptions::default()
    }
}

/// `steps` implicit Euler steps of `model` from `state`: every state, start included.
fn trace<M>(
    model: &M,
    state: M::State,
    dt: f64,
    steps: usize,
    newton: NewtonOptions,
) -> odyn::Result<Vec<M::State>>
where
    M: Jacobian,
    M::State: Clone,
{
    let mut stepper = Stepper::<M, ImplicitEuler<M>>::with_newton(model, state, 0.0, dt, &newton)?;
    let mut states = vec![stepper.state().clone()];
    for _ in 0..steps {
        stepper.step()?;
        states.push(stepper.state().clone());
    }
    Ok(states)
}

/// Largest |difference| of two states' components.
fn gap<const D: usize>(a: &ParticleState<D>, b: &ParticleState<D>) -> f64 {
    crate::common::max_abs_difference(a.as_slice(), b.as_slice())
}

fn bits<const D: usize>(s: &ParticleState<D>) -> Vec<u64> {
    s.as_slice().iter().map(|c| c.to_bits()).collect()
}

fn kinetic<const D: usize>(s: &ParticleState<D>, m: &[f64]) -> f64 {
    let v = s.velocities().iter().zip(m);
    v.map(|(v, m)| 0.5 * m * v.norm_squared()).sum()
}

// ---------------------------------------------------------------------------------------------
// Models.

/// 3-D, a linear pair force fₐ = k·(x_b − xₐ) on every link (k > 0 attracts: a zero-rest-length
/// spring; k < 0 repels), plus a constant pair force `push` on a (−push on b), whose Jacobian is
/// zero.
#[system(integrator = ImplicitEuler, dt = 0.01)]
#[derive(Clone, Debug)]
struct Linear3 {
    #[position]
    x: Vec<Vector3<f64>>,
    #[velocity]
    v: Vec<Vector3<f64>>,
    #[mass]
    m: Vec<f64>,
    #[pinned]
    pins: Vec<usize>,
    links: Vec<[usize; 2]>,
    k: f64,
    push: Vector3<f64>,
}

#[system]
impl Linear3 {
    #[pair(links)]
    fn pull(&self, _l: &[usize; 2], xa: Vector3<f64>, xb: Vector3<f64>) -> Vector3<f64> {
        (xb - xa) * self.k + self.push
    }
}

fn linear3(k: f64, m: f64) -> Linear3 {
    Linear3 {
        x: vec![Vector3::zeros(), Vector3::new(1.0, 0.0, 0.0)],
        v: vec![Vector3::zeros(); 2],
        m: vec![m; 2],
        pins: vec![],
        links: vec![[0, 1]],
        k,
        push: Vector3::zeros(),
    }
}

/// ½k|d|² over links + ½Σm|v|² (the push off).
fn linear3_energy(model: &Linear3, s: &ParticleState<3>) -> f64 {
    let x = s.positions();
    let springs: f64 = model
        .links
        .iter()
        .map(|[a, b]| 0.5 * model.k * (x[*b] - x[*a]).norm_squared())
        .sum();
    springs + kinetic(s, &model.m)
}

/// 3-D softened gravity between every pair listed: fₐ = G·mₐ·m_b·d/(|d|² + ε²)^{3/2}.
#[system(integrator = ImplicitEuler, dt = 0.01)]
#[derive(Clone, Debug)]
struct Gravity {
    #[position]
    x: Vec<Vector3<f64>>,
    #[velocity]
    v: Vec<Vector3<f64>>,
    #[mass]
    m: Vec<f64>,
    pairs: Vec<[usize; 2]>,
    g: f64,
    eps: f64,
}

#[system]
impl Gravity {
    #[pair(pairs)]
    fn attract(&self, l: &[usize; 2], xa: Vector3<f64>, xb: Vector3<f64>) -> Vector3<f64> {
        let d = xb - xa;
        let r2 = d.norm_squared() + self.eps * self.eps;
        d * (self.g * self.m[l[0]] * self.m[l[1]] / (r2 * r2.sqrt()))
    }
}

fn gravity_energy(model: &Gravity, s: &ParticleState<3>) -> f64 {
    let x = s.positions();
    let pot: f64 = model
        .pairs
        .iter()
        .map(|&[a, b]| {
            let r2 = (x[b] - x[a]).norm_squared() + model.eps * model.eps;
            -model.g * model.m[a] * model.m[b] / r2.sqrt()
        })
        .sum();
    pot + kinetic(s, &model.m)
}

/// Two unit masses on a circular orbit of separation 1 (G = 1: relative speed √2, period
/// 2π/√2 ≈ 4.44 s, Kepler), ε = 1e-3.
fn binary() -> Gravity {
    let u = 0.5 * 2f64.sqrt();
    Gravity {
        x: vec![Vector3::new(-0.5, 0.0, 0.0), Vector3::new(0.5, 0.0, 0.0)],
        v: vec![Vector3::new(0.0, -u, 0.0), Vector3::new(0.0, u, 0.0)],
        m: vec![1.0; 2],
        pairs: vec![[0, 1]],
        g: 1.0,
        eps: 1e-3,
    }
}

/// 2-D, particle forces only (no links): a charge in a magnetic field B ẑ, f = q·v × B =
/// qB·(v_y, −v_x), and an optional harmonic trap −κ·x.
#[system(integrator = ImplicitEuler, dt = 0.01)]
#[derive(Clone, Debug)]
struct Charges {
    #[position]
    x: Vec<Vector2<f64>>,
    #[velocity]
    v: Vec<Vector2<f64>>,
    #[mass]
    m: Vec<f64>,
    qb: f64,
    trap: f64,
}

#[system]
impl Charges {
    #[particle]
    fn lorentz(&self, x: Vector2<f64>, v: Vector2<f64>) -> Vector2<f64> {
        Vector2::new(v.y, -v.x) * self.qb - x * self.trap
    }
}

/// 2-D spring with a rest length and an isotropic damper fₐ = c·(v_b − vₐ) between the ends.
#[system(integrator = ImplicitEuler, dt = 0.01)]
#[derive(Clone, Debug)]
struct Damped2 {
    #[position]
    x: Vec<Vector2<f64>>,
    #[velocity]
    v: Vec<Vector2<f64>>,
    #[mass]
    m: Vec<f64>,
    #[pinned]
    pins: Vec<usize>,
    springs: Vec<Spring>,
    c: f64,
}

#[system]
impl Damped2 {
    #[pair(springs)]
    fn spring(
        &self,
        s: &Spring,
        xa: Vector2<f64>,
        xb: Vector2<f64>,
        va: Vector2<f64>,
        vb: Vector2<f64>,
    ) -> Vector2<f64> {
        let d = xb - xa;
        d.normalize() * (s.stiffness * (d.norm() - s.rest)) + (vb - va) * self.c
    }
}

/// A 2-D rope of `n` particles 0.05 m apart along x, pinned at 0, springs k, no damping.
fn rope(n: usize, k: f64, c: f64) -> Damped2 {
    let x: Vec<_> = (0..n).map(|i| Vector2::new(0.05 * i as f64, 0.0)).collect();
    Damped2 {
        springs: (0..n - 1)
            .map(|i| Spring::at_rest(&x, i, i + 1, k, 0.0))
            .collect(),
        v: vec![Vector2::zeros(); n],
        m: vec![0.005; n],
        pins: vec![0],
        c,
        x,
    }
}

fn spring_energy(model: &Damped2, s: &ParticleState<2>) -> f64 {
    let x = s.positions();
    let springs: f64 = model
        .springs
        .iter()
        .map(|sp| 0.5 * sp.stiffness * ((x[sp.b] - x[sp.a]).norm() - sp.rest).powi(2))
        .sum();
    springs + kinetic(s, &model.m)
}
