//! The generated Jacobian against the alternatives a user would otherwise write: by hand,
//! forward-mode automatic differentiation (num-dual), and central finite differences; and the cost
//! of one implicit Euler step.
//!
//! `cargo bench --bench jacobian`. Compare medians within a group, measured side by side. Every
//! variant is `#[inline(never)]`, so each pays one call and none is folded into divan's loop.

mod chain;
mod step;

use std::hint::black_box;

use nalgebra::{Matrix2, Matrix3, Matrix4, SVector};
use num_dual::{DualNum, DualSVec64, jacobian};
use odyn::integrators::{ImplicitEuler, Integrator, Rk4};
use odyn::prelude::*;
use odyn::{Jacobian, NewtonOptions, Stats, nalgebra};

use scenes::*;

fn main() {
    divan::main();
}

fn spring() -> (Spring, SpringState) {
    black_box((
        Spring {
            x: 0.0,
            v: 0.0,
            k: 50.0,
            b: 0.5,
            m: 1.0,
        },
        SpringState { x: 0.3, v: -1.1 },
    ))
}

fn kepler() -> (Kepler, KeplerState) {
    let state = KeplerState {
        r: Vector2::new(0.6, -0.8),
        v: Vector2::new(0.4, 1.1),
    };
    black_box((
        Kepler {
            r: Vector2::zeros(),
            v: Vector2::zeros(),
            gm: 1.0,
        },
        state,
    ))
}

fn lorenz() -> (Lorenz, LorenzState) {
    let model = Lorenz {
        x: 0.0,
        y: 0.0,
        z: 0.0,
        sigma: 10.0,
        rho: 28.0,
        beta: 8.0 / 3.0,
    };
    black_box((
        model,
        LorenzState {
            x: 1.5,
            y: -2.0,
            z: 20.0,
        },
    ))
}

/// Kepler's problem as `scenes::Kepler` writes it, its Jacobian by `jacobian = dual`.
#[system(jacobian = dual)]
#[derive(Clone, Copy)]
struct DualKepler {
    #[position]
    r: Vector2<f64>,
    #[velocity]
    v: Vector2<f64>,
    gm: f64,
}

#[system]
impl DualKepler {
    fn acceleration(&self) -> Vector2<f64> {
        -self.gm * self.r / self.r.norm().powi(3)
    }
}

/// Lorenz's system as `scenes::Lorenz` writes it, its Jacobian by `jacobian = dual`.
#[system(jacobian = dual)]
#[derive(Clone, Copy)]
struct DualLorenz {
    #[state]
    x: f64,
    #[state]
    y: f64,
    #[state]
    z: f64,
    sigma: f64,
    rho: f64,
    beta: f64,
}

#[system]
impl DualLorenz {
    fn derivative(&self) -> DualLorenzState {
        DualLorenzState {
            x: self.sigma * (self.y - self.x),
            y: self.x * (self.rho - self.z) - self.y,
            z: self.x * self.y - self.beta * self.z,
        }
    }
}

fn dual_kepler() -> (DualKepler, DualKeplerState) {
    let (k, y) = kepler();
    black_box((
        DualKepler {
            r: k.r,
            v: k.v,
            gm: k.gm,
        },
        DualKeplerState { r: y.r, v: y.v },
    ))
}

fn dual_lorenz() -> (DualLorenz, DualLorenzState) {
    let (l, y) = lorenz();
    black_box((
        DualLorenz {
            x: l.x,
            y: l.y,
            z: l.z,
            sigma: l.sigma,
            rho: l.rho,
            beta: l.beta,
        },
        DualLorenzState {
            x: y.x,
            y: y.y,
            z: y.z,
        },
    ))
}

fn generated<M: Jacobian>((model, state): (M, M::State)) -> M::Matrix {
    let mut j = model.jacobian_matrix(&state);
    model.jacobian(0.0, &state, &mut j);
    j
}

/// Central differences, as `#[system(jacobian = finite_differences)]` takes them: two
/// derivative evaluations per state component (`odyn::__private::central_differences`).
fn central<M: Jacobian>((model, y): (M, M::State)) -> M::Matrix
where
    M::Matrix: std::ops::IndexMut<(usize, usize), Output = f64>,
    M::State: Copy,
{
    let mut j = model.jacobian_matrix(&y);
    odyn::__private::central_differences(&model, 0.0, &y, |r, c, v| j[(r, c)] = v);
    j
}

mod spring_jacobian {
    use super::*;

    #[divan::bench]
    #[inline(never)]
    fn generated() -> Matrix2<f64> {
        super::generated(spring())
    }

    #[divan::bench]
    #[inline(never)]
    fn generated_direct() -> Matrix2<f64> {
        let (m, s) = spring();
        let mut j = Matrix2::zeros();
        m.jacobian(0.0, &s, &mut j);
        j
    }

    #[divan::bench]
    #[inline(never)]
    fn hand_written() -> Matrix2<f64> {
        let (s, _) = spring();
        Matrix2::new(0.0, 1.0, -s.k / s.m, -s.b / s.m)
    }

    #[divan::bench]
    #[inline(never)]
    fn num_dual() -> Matrix2<f64> {
        let (s, y) = spring();
        let f = |y: SVector<DualSVec64<2>, 2>| {
            SVector::from([y[1], (y[0] * (-s.k) - y[1] * s.b) / s.m])
        };
        jacobian(f, &SVector::from([y.x, y.v])).1
    }

    #[divan::bench]
    #[inline(never)]
    fn central_differences() -> Matrix2<f64> {
        central(spring())
    }
}

mod kepler_jacobian {
    use super::*;

    #[divan::bench]
    #[inline(never)]
    fn generated() -> Matrix4<f64> {
        super::generated(kepler())
    }

    /// ∂a/∂r = GM·(3·r·rᵀ/|r|⁵ − I/|r|³), the block every N-body code writes by hand.
    #[divan::bench]
    #[inline(never)]
    fn hand_written() -> Matrix4<f64> {
        let (k, y) = kepler();
        let r = y.r;
        let d2 = r.norm_squared();
        let d = d2.sqrt();
        let (inv3, inv5) = (1.0 / (d2 * d), 1.0 / (d2 * d2 * d));
        let mut j = Matrix4::zeros();
        j[(0, 2)] = 1.0;
        j[(1, 3)] = 1.0;
        for a in 0..2 {
            for b in 0..2 {
                let delta = if a == b { 1.0 } else { 0.0 };
                j[(2 + a, b)] = k.gm * (3.0 * r[a] * r[b] * inv5 - delta * inv3);
            }
        }
        j
    }

    #[divan::bench]
    #[inline(never)]
    fn num_dual() -> Matrix4<f64> {
        let (k, y) = kepler();
        let f = |y: SVector<DualSVec64<4>, 4>| {
            let d3 = (y[0] * y[0] + y[1] * y[1]).sqrt().powi(3);
            SVector::from([y[2], y[3], y[0] * (-k.gm) / d3, y[1] * (-k.gm) / d3])
        };
        jacobian(f, &SVector::from([y.r.x, y.r.y, y.v.x, y.v.y])).1
    }

    /// `#[system(jacobian = dual)]` on the model's own code: one dual evaluation per column.
    #[divan::bench]
    #[inline(never)]
    fn jacobian_dual() -> Matrix4<f64> {
        super::generated(dual_kepler())
    }

    #[divan::bench]
    #[inline(never)]
    fn central_differences() -> Matrix4<f64> {
        central(kepler())
    }
}

mod lorenz_jacobian {
    use super::*;

    #[divan::bench]
    #[inline(never)]
    fn generated() -> Matrix3<f64> {
        super::generated(lorenz())
    }

    #[divan::bench]
    #[inline(never)]
    fn hand_written() -> Matrix3<f64> {
        let (l, s) = lorenz();
        Matrix3::new(
            -l.sigma,
            l.sigma,
            0.0,
            l.rho - s.z,
            -1.0,
            -s.x,
            s.y,
            s.x,
            -l.beta,
        )
    }

    #[divan::bench]
    #[inline(never)]
    fn num_dual() -> Matrix3<f64> {
        let (l, s) = lorenz();
        let f = |y: SVector<DualSVec64<3>, 3>| {
            SVector::from([
                (y[1] - y[0]) * l.sigma,
                y[0] * (-y[2] + l.rho) - y[1],
                y[0] * y[1] - y[2] * l.beta,
            ])
        };
        jacobian(f, &SVector::from([s.x, s.y, s.z])).1
    }

    /// `#[system(jacobian = dual)]` on the model's own code: one dual evaluation per column.
    #[divan::bench]
    #[inline(never)]
    fn jacobian_dual() -> Matrix3<f64> {
        super::generated(dual_lorenz())
    }

    #[divan::bench]
    #[inline(never)]
    fn central_differences() -> Matrix3<f64> {
        central(lorenz())
    }
}
