//! Models above the stack-matrix size (32 components): with few structural non-zeros their
//! Jacobian is one expression per entry, with many (over 4096) it comes from coloured forward mode
//! (`macros/src/sparsity.rs`). Both checked here against central differences, with the
//! structural non-zeros the colouring relies on, and end to end through the implicit methods.
#![allow(missing_docs)]

use crate::common;

use common::*;
use odyn::nalgebra::SVector;
use odyn::prelude::*;

/// ẏ = −k·y·|y|² + sin(t)·y/|y|: every component couples to every other (72² = 5184 non-zeros:
/// forward mode, one column per group), and f reads the time.
#[system(integrator = Rodas5P)]
pub struct Dense {
    #[state]
    pub y: SVector<f64, 72>,
    pub k: f64,
}

#[system]
impl Dense {
    fn derivative(&self, t: f64) -> DenseState {
        DenseState {
            y: -self.y * (self.k * self.y.norm_squared()) + self.y.normalize() * t.sin(),
        }
    }
}

/// 24 damped oscillators with a cubic friction, q̇ = p, ṗ = −k·q − c·p∘p∘q, plus one `min` on a
/// component: a sparse Jacobian of 72 non-zeros, one expression each.
#[system(integrator = Rodas5P)]
pub struct Chain {
    #[state]
    pub q: SVector<f64, 24>,
    #[state]
    pub p: SVector<f64, 24>,
    pub k: f64,
    pub c: f64,
}

#[system]
impl Chain {
    fn derivative(&self) -> ChainState {
        let mut dp =
            -self.q * self.k - self.p.component_mul(&self.p).component_mul(&self.q) * self.c;
        dp[0] = dp[0].min(self.q[0]);
        ChainState { q: self.p, p: dp }
    }
}

/// Eight independent blocks ȧ = −a·|a|², each dense within itself: 8·24² = 4608 non-zeros, so
/// forward mode, and the colouring seeds one column of every block together (24 groups).
#[system(integrator = Rodas5P)]
pub struct Blocks {
    #[state]
    pub a: SVector<f64, 24>,
    #[state]
    pub b: SVector<f64, 24>,
    #[state]
    pub c: SVector<f64, 24>,
    #[state]
    pub d: SVector<f64, 24>,
    #[state]
    pub e: SVector<f64, 24>,
    #[state]
    pub f: SVector<f64, 24>,
    #[state]
    pub g: SVector<f64, 24>,
    #[state]
    pub h: SVector<f64, 24>,
}

#[system]
impl Blocks {
    fn derivative(&self) -> BlocksState {
        BlocksState {
            a: -self.a * self.a.norm_squared(),
            b: -self.b * self.b.norm_squared(),
            c: -self.c * self.c.norm_squared(),
            d: -self.d * self.d.norm_squared(),
            e: -self.e * self.e.norm_squared(),
            f: -self.f * self.f.norm_squared(),
            g: -self.g * self.g.norm_squared(),
            h: -self.h * self.h.norm_squared(),
        }
    }
}

fn dense() -> Dense {
    Dense {
        y: SVector::from_fn(|i, _| 0.1 + 0.01 * i as f64),
        k: 2.0,
    }
}

impl Blocks {
    fn default_state() -> Blocks {
        let v = SVector::from_element(0.1);
        Blocks {
            a: v,
            b: v,
            c: v,
            d: v,
            e: v,
            f: v,
            g: v,
            h: v,
        }
    }
}

fn chain() -> Chain {
    Chain {
        q: SVector::from_fn(|i, _| (i as f64 * 0.3).sin()),
        p: SVector::from_fn(|i, _| (i as f64 * 0.7).cos()),
        k: 4.0,
        c: 0.5,
    }
}

#[test]
fn forward_mode_jacobians_match_finite_differences() {
    check(&dense(), 0.7, 5, |r| DenseState {
        y: SVector::from_fn(|_, _| r.uniform(-1.0, 1.0)),
    });
    assert_eq!(Dense::NONZEROS.len(), 72 * 72);
    let draw = |r: &mut Rng| SVector::<f64, 24>::from_fn(|_, _| r.uniform(-1.0, 1.0));
    check(&Blocks::default_state(), 0.0, 3, |r| BlocksState {
        a: draw(r),
        b: draw(r),
        c: draw(r),
        d: draw(r),
        e: draw(r),
        f: draw(r),
        g: draw(r),
        h: draw(r),
    });
    assert_eq!(Blocks::NONZEROS.len(), 8 * 24 * 24);
    check(&chain(), 0.0, 5, |r| ChainState {
        q: SVector::from_fn(|_, _| r.uniform(-1.0, 1.0)),
        p: SVector::from_fn(|_, _| r.uniform(-1.0, 1.0)),
    });
    // q̇ᵢ ← pᵢ; ṗᵢ ← qᵢ, pᵢ: 3 × 24, and the `min` adds nothing new.
    assert_eq!(Chain::NONZEROS.len(), 3 * 24);
}

/// ∂f/∂t of a big model is exact too: cos(t)·y/|y| against a central difference in t.
#[test]
fn big_models_have_an_exact_time_derivative() {
    let model = dense();
    let (t, y) = (0.7, model.state());
    let mut exact = y;
    model.time_derivative(t, &y, &mut exact);
    let expected = y.y.normalize() * t.cos();
    assert!(
        (exact.y - expected).amax() < 1e-14,
        "{}",
        (exact.y - expected).amax()
    );
}

/// Parameters read whole: `self.rates` and `self.w` put 300 and 3000 values in the Jacobian's
/// prologue, and its straight line has 300 products. One `let` each, nested 3600 deep, overflowed
/// rustc's stack in the dev profile (LLVM walks nested scopes' debuginfo recursively); they are
/// now bound at most 256 to a `let` and 256 `let`s to a block (`macros/src/generate/code.rs`).
#[system(integrator = ImplicitEuler)]
pub struct Weighted {
    #[state]
    pub z: SVector<f64, 300>,
    pub rates: SVector<f64, 300>,
    pub w: [f64; 3000],
}

#[system]
impl Weighted {
    fn derivative(&self) -> WeightedState {
        let w = self.w;
        WeightedState {
            z: -self.rates.component_mul(&self.z) * w[2999],
        }
    }
}

#[test]
fn many_parameters_and_values_compile_and_differentiate() {
    let mut w = [0.0; 3000];
    w[2999] = 1.5;
    let model = Weighted {
        z: SVector::from_fn(|i, _| (i as f64 * 0.1).sin()),
        rates: SVector::from_fn(|i, _| 1.0 + i as f64 * 0.01),
        w,
    };
    let y = model.state();
    let mut jacobian = model.jacobian_matrix(&y);
    model.jacobian(0.0, &y, &mut jacobian);
    assert_eq!(Weighted::NONZEROS.len(), 300);
    for &(i, j) in Weighted::NONZEROS {
        assert_eq!(i, j);
        let expected = -model.rates[i] * 1.5;
        let entry = odyn::DenseMatrix::entry(&jacobian, i, i);
        assert!(
            (entry - expected).abs() <= 1e-15 * expected.abs(),
            "{i}: {entry} vs {expected}"
        );
    }
}

/// The implicit methods run on forward-mode Jacobians and agree with an explicit reference:
/// Rodas5P and Rosenbrock23 at rtol 1e-8 against DOP853 at rtol 1e-12. A global error of
/// ~100× the local tolerance is normal for an order-2 method over many steps (Rosenbrock23
/// measured 2.8e-6 here), so its bound is 1e-5; Rodas5P's is 1e-6.
#[test]
fn implicit_methods_run_on_big_models() {
    for model_run in [
        |m: Method, rtol: f64| -> Vec<f64> {
            let run = dense()
                .simulate()
                .integrator(m)
                .tolerances(rtol, rtol * 1e-2)
                .duration(2.0)
                .run()
                .unwrap();
            run.samples.last().unwrap().state.y.as_slice().to_vec()
        },
        |m: Method, rtol: f64| -> Vec<f64> {
            let run = chain()
                .simulate()
                .integrator(m)
                .tolerances(rtol, rtol * 1e-2)
                .duration(2.0)
                .run()
                .unwrap();
            run.samples.last().unwrap().state.p.as_slice().to_vec()
        },
    ] {
        let reference = model_run(Method::Dop853, 1e-12);
        for (method, bound) in [(Method::Rodas5P, 1e-6), (Method::Rosenbrock23, 1e-5)] {
            let y = model_run(method, 1e-8);
            let error = y
                .iter()
                .zip(&reference)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(error < bound, "{method:?}: {error:e}");
        }
    }
}
