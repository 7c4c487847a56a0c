//! State fields that are arrays of vectors or of arrays (`[Vector3<f64>; 6]`, `[[f64; 2]; 3]`):
//! their layout, their exact Jacobians, and the same run as the same model written one axis
//! per array.

use crate::common::{self, Rng};

use odyn::prelude::*;
use odyn::{Jacobian, Method};
use scenes::{SolarSystem, SolarSystemByAxis, SolarSystemByAxisState, SolarSystemState};

/// The Sun, Jupiter and Saturn of [`SolarSystem::outer`] alone, with the generated Jacobian
/// (`SolarSystem` itself is explicit-only).
#[system]
#[derive(Clone, Copy, Debug)]
pub(crate) struct ThreeBodies {
    #[position]
    pub(crate) r: [Vector3<f64>; 3],
    #[velocity]
    pub(crate) v: [Vector3<f64>; 3],
    pub(crate) m: [f64; 3],
    pub(crate) g: f64,
}

#[system]
impl ThreeBodies {
    fn acceleration(&self) -> [Vector3<f64>; 3] {
        let mut a = [Vector3::<f64>::zeros(); 3];
        for i in 0..3 {
            for j in (i + 1)..3 {
                let d = self.r[j] - self.r[i];
                let r2 = d.x * d.x + d.y * d.y + d.z * d.z;
                let s = self.g / (r2 * r2.sqrt());
                a[i] += d * (self.m[j] * s);
                a[j] -= d * (self.m[i] * s);
            }
        }
        a
    }
}

pub(crate) fn three_bodies() -> ThreeBodies {
    let s = SolarSystem::outer();
    ThreeBodies {
        r: [s.r[0], s.r[1], s.r[2]],
        v: [s.v[0], s.v[1], s.v[2]],
        m: [s.m[0], s.m[1], s.m[2]],
        g: s.g,
    }
}

/// A planar chain of four unit masses joined by springs (stiffness 50, rest length 1), the
/// first spring anchored at the origin, under gravity.
#[system]
#[derive(Clone, Copy)]
pub(crate) struct Chain {
    #[position]
    pub(crate) q: [Vector2<f64>; 4],
    #[velocity]
    pub(crate) p: [Vector2<f64>; 4],
    pub(crate) k: f64,
}

#[system]
impl Chain {
    fn acceleration(&self) -> [Vector2<f64>; 4] {
        let mut a = [Vector2::new(0.0, -9.81); 4];
        let mut previous = Vector2::<f64>::zeros();
        for i in 0..4 {
            let d = self.q[i] - previous;
            let length = d.norm();
            let f = d * (self.k * (length - 1.0) / length);
            a[i] -= f;
            if i > 0 {
                a[i - 1] += f;
            }
            previous = self.q[i];
        }
        a
    }
}

/// Three Brusselator cells in a ring, each `[u, v]`, coupled by diffusion of u; each row is
/// written component by component (`dc[i][0] = …`).
#[system]
#[derive(Clone, Copy)]
struct Cells {
    #[state]
    c: [[f64; 2]; 3],
    a: f64,
    b: f64,
    d: f64,
}

#[system]
#[allow(
    clippy::needless_range_loop,
    reason = "rows written component by component are the form under test"
)]
impl Cells {
    fn derivative(&self) -> CellsState {
        let mut dc = [[0.0; 2]; 3];
        for i in 0..3 {
            let [u, v] = self.c[i];
            let left = self.c[(i + 2) % 3][0];
            let right = self.c[(i + 1) % 3][0];
            dc[i][0] = self.a - (self.b + 1.0) * u + u * u * v + self.d * (left - 2.0 * u + right);
            dc[i][1] = self.b * u - u * u * v;
        }
        CellsState { c: dc }
    }
}

#[test]
fn arrays_of_vectors_lay_out_row_after_row() {
    let s = SolarSystem::outer().state();
    assert_eq!(SolarSystemState::LEN, 36);
    assert_eq!(s.as_slice()[3..6], *s.r[1].as_slice());
    assert_eq!(s.as_slice()[18 + 5], s.v[1].z);
    assert_eq!(s.component_name(4), "r[1][1]");
    assert_eq!(s.component_name(35), "v[5][2]");
    let cells = CellsState {
        c: [[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]],
    };
    assert_eq!(cells.as_slice(), &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    assert_eq!(cells.component_name(3), "c[1][1]");
}

#[test]
fn jacobians_of_arrays_of_vectors_match_finite_differences() {
    let mut bodies = three_bodies();
    // Unit masses and G: the entries of the real system span 10⁻¹³ to 10⁻⁴, below what the
    // central differences resolve against their own rounding.
    bodies.m = [1.0, 0.5, 0.3];
    bodies.g = 1.0;
    let start = bodies.state();
    common::check(&bodies, 0.0, 20, |r: &mut Rng| {
        let mut s = start;
        for q in s.r.iter_mut().chain(s.v.iter_mut()) {
            *q += Vector3::new(
                r.uniform(-0.5, 0.5),
                r.uniform(-0.5, 0.5),
                r.uniform(-0.5, 0.5),
            );
        }
        s
    });
    // Accelerations read every position and no velocity.
    assert!(ThreeBodies::NONZEROS.contains(&(9, 3)));
    assert!(!ThreeBodies::NONZEROS.iter().any(|&(r, c)| r >= 9 && c >= 9));

    let chain = Chain {
        q: std::array::from_fn(|i| Vector2::new(1.1 * (i + 1) as f64, 0.0)),
        p: [Vector2::zeros(); 4],
        k: 50.0,
    };
    common::check(&chain, 0.0, 50, |r: &mut Rng| ChainState {
        q: std::array::from_fn(|i| {
            Vector2::new(
                1.1 * (i + 1) as f64 + r.uniform(-0.3, 0.3),
                r.uniform(-1.0, 1.0),
            )
        }),
        p: std::array::from_fn(|_| Vector2::new(r.uniform(-1.0, 1.0), r.uniform(-1.0, 1.0))),
    });
    let cells = Cells {
        c: [[1.0, 3.0]; 3],
        a: 1.0,
        b: 3.0,
        d: 0.2,
    };
    common::check(&cells, 0.0, 50, |r: &mut Rng| CellsState {
        c: std::array::from_fn(|_| [r.uniform(0.1, 3.0), r.uniform(0.1, 5.0)]),
    });
}

/// Every explicit method runs the `[Vector3<f64>; 6]` solar system and the form with one array
/// per axis alike: the same bits at a fixed step, where the arithmetic is the same; adaptive
/// ones agree to rounding (their error norm sums the components in the other layout's order).
#[test]
fn an_array_of_vectors_runs_every_explicit_method_as_the_axis_arrays_do() {
    let vectors = SolarSystem::outer();
    let axes = SolarSystemByAxis::outer();
    assert_eq!(SolarSystemByAxis::by_axis(&vectors.state()), axes.state());
    let (dt, steps) = (10.0, 200_u64);
    for method in Method::ALL.into_iter().filter(|m| !m.info().needs_jacobian) {
        let run = vectors
            .simulate()
            .integrator(method)
            .dt(dt)
            .steps(steps)
            .run()
            .unwrap_or_else(|e| panic!("{method}: {e}"));
        let last = SolarSystemByAxis::by_axis(&run.last().state);
        let by_axis = axes
            .simulate()
            .integrator(method)
            .dt(dt)
            .steps(steps)
            .run()
            .unwrap();
        let expected = by_axis.last().state;
        if method.info().adaptive {
            for (a, b) in last.as_slice().iter().zip(expected.as_slice()) {
                assert!(
                    (a - b).abs() <= 1e-12 * (1.0 + b.abs()),
                    "{method}: {a} against {b}"
                );
            }
        } else {
            assert_eq!(run.samples.len(), by_axis.samples.len(), "{method}");
            let bits = |s: &SolarSystemByAxisState| {
                s.as_slice().iter().map(|x| x.to_bits()).collect::<Vec<_>>()
            };
            assert_eq!(bits(&last), bits(&expected), "{method}");
        }
    }
}

/// The implicit methods run an array-of-vectors model on its generated Jacobian at their
/// orders: Sun, Jupiter and Saturn over 2 000 days, halving dt = 10 days, against DOP853 at
/// rtol = atol = 1e-13 (its error is far below every fixed-step error compared with it).
#[test]
fn an_array_of_vectors_runs_the_implicit_methods_at_their_orders() {
    let bodies = three_bodies();
    let (dt, steps) = (10.0, 200_u64);
    let reference = bodies
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-13, 1e-13)
        .duration(dt * steps as f64)
        .run()
        .unwrap();
    let reference = reference.last().state;
    let error = |dt: f64, steps: u64, method: Method| {
        let run = bodies
            .simulate()
            .integrator(method)
            .dt(dt)
            .steps(steps)
            .run()
            .unwrap_or_else(|e| panic!("{method}: {e}"));
        let e = run
            .last()
            .state
            .as_slice()
            .iter()
            .zip(reference.as_slice())
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(e.is_finite(), "{method}, {steps} steps: {e}");
        e
    };
    for method in Method::ALL.into_iter().filter(|m| m.info().needs_jacobian) {
        // Halving the step divides the error by about 2ᵖ (p, the method's order).
        let ratio = error(dt, steps, method) / error(dt / 2.0, 2 * steps, method);
        let (measured, order) = (ratio.log2(), f64::from(method.info().order));
        // Measured: implicit Euler 1.06, Rosenbrock23 1.99, Rodas5P 5.53, BDF (order 2 at a
        // fixed step) 2.00.
        assert!(
            measured > order - 0.3 && measured < order + 1.0,
            "{method}: order {measured}, expected {order}"
        );
    }
}
