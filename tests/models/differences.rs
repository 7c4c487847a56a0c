//! `#[system(jacobian = finite_differences)]`: a model whose code the macro cannot
//! differentiate (here a function of a vector it cannot see inside) still runs every implicit
//! method, on a Jacobian of central differences, against the same model made exact by marking
//! the function `#[odyn::function]`.

use crate::common::{self, Rng};

use odyn::nalgebra::Vector3;
use odyn::prelude::*;
use odyn::{Jacobian, Method};

/// The magnetic field of a dipole of moment m = ẑ at the origin, B = (3(m·r̂)r̂ − m)/|r|³
/// (Jackson, *Classical Electrodynamics*, 3rd ed., eq. (5.56)); a function of a vector, which
/// the macro cannot see inside unless it is marked `#[odyn::function]`.
fn dipole(r: Vector3<f64>) -> Vector3<f64> {
    let d = r.norm();
    let rhat = r / d;
    (3.0 * rhat.z * rhat - Vector3::z()) / (d * d * d)
}

/// A charged particle trapped in the dipole's field (a Störmer orbit), r̈ = q·v × B(r), the field
/// from the function above: by finite differences.
#[system(jacobian = finite_differences)]
#[derive(Clone, Copy, Debug)]
struct Trapped {
    #[position]
    r: Vector3<f64>,
    #[velocity]
    v: Vector3<f64>,
    q: f64,
}

#[system]
impl Trapped {
    fn acceleration(&self) -> Vector3<f64> {
        self.q * self.v.cross(&dipole(self.r))
    }
}

/// [`Trapped`] with the field a marked helper: the macro differentiates it exactly.
#[system]
#[derive(Clone, Copy, Debug)]
struct Exact {
    #[position]
    r: Vector3<f64>,
    #[velocity]
    v: Vector3<f64>,
    q: f64,
}

#[system]
impl Exact {
    fn acceleration(&self) -> Vector3<f64> {
        self.q * self.v.cross(&self.field(self.r))
    }

    #[odyn::function]
    fn field(&self, r: Vector3<f64>) -> Vector3<f64> {
        let d = r.norm();
        let rhat = r / d;
        (3.0 * rhat.z * rhat - Vector3::new(0.0, 0.0, 1.0)) / (d * d * d)
    }
}

fn start(r: &mut Rng) -> (Vector3<f64>, Vector3<f64>) {
    (
        Vector3::new(
            r.uniform(1.0, 2.0),
            r.uniform(-0.5, 0.5),
            r.uniform(-0.5, 0.5),
        ),
        Vector3::new(
            r.uniform(-0.3, 0.3),
            r.uniform(0.2, 0.5),
            r.uniform(-0.3, 0.3),
        ),
    )
}

#[test]
fn a_jacobian_of_finite_differences_matches_the_exact_one() {
    const { assert!(!<Trapped as Jacobian>::EXACT && <Exact as Jacobian>::EXACT) };
    const { assert!(!<Trapped as Jacobian>::TIME_DEPENDENT) };
    let (model, exact) = (
        Trapped {
            r: Vector3::zeros(),
            v: Vector3::zeros(),
            q: 2.0,
        },
        Exact {
            r: Vector3::zeros(),
            v: Vector3::zeros(),
            q: 2.0,
        },
    );
    let mut rng = Rng(5);
    for _ in 0..50 {
        let (r, v) = start(&mut rng);
        let (y, z) = (TrappedState { r, v }, ExactState { r, v });
        let (mut j, mut k) = (model.jacobian_matrix(&y), exact.jacobian_matrix(&z));
        model.jacobian(0.0, &y, &mut j);
        exact.jacobian(0.0, &z, &mut k);
        // Central differences at h = ε^⅓·max(1, |yⱼ|) ≈ 6e-6: truncation h²·|f‴|/6 and rounding
        // ε·|f|/h, both below 1e-9 of the largest entry for this field (|f| ≲ 10 at |r| ≥ 1).
        let scale = k.amax();
        assert!((j - k).amax() <= 1e-8 * scale, "{}", (j - k).amax() / scale);
    }
    // And against `common::check`'s own differences (a different step).
    common::check(&model, 0.0, 20, |r| {
        let (r, v) = start(r);
        TrappedState { r, v }
    });
}

/// Every method that needs a Jacobian runs the model of finite differences and lands where the
/// exact model does, to the run's tolerance. Newton-based methods (implicit Euler, BDF) iterate
/// to the same solution whatever the Jacobian; Rosenbrock methods build J into their stages, so
/// theirs differ at the level of J's error times the step (≲ 1e-9 here).
#[test]
fn every_implicit_method_runs_on_finite_differences() {
    let (r, v) = (Vector3::new(1.5, 0.0, 0.2), Vector3::new(0.0, 0.4, 0.1));
    let model = Trapped { r, v, q: 2.0 };
    let exact = Exact { r, v, q: 2.0 };
    for method in Method::ALL.into_iter().filter(|m| m.info().needs_jacobian) {
        let ours = model
            .simulate()
            .integrator(method)
            .dt(1e-3)
            .duration(2.0)
            .run()
            .unwrap_or_else(|e| panic!("{method}: {e}"));
        let theirs = exact
            .simulate()
            .integrator(method)
            .dt(1e-3)
            .duration(2.0)
            .run()
            .unwrap();
        let (a, b) = (ours.last().state, theirs.last().state);
        let difference = (a.r - b.r).amax().max((a.v - b.v).amax());
        assert!(difference < 1e-8, "{method}: {difference}");
    }
}
