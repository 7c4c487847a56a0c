//! Tsit5: Tsitouras' 5(4) Runge–Kutta pair with its free order-4 interpolant.

use super::explicit_rk::{ExplicitRk, Tableau, weighted};
use super::tableaux::tsit5::{A, B, BTILDE, C, DENSE, STAGES};
use super::{DenseStep, Step, axpy};
use crate::{Controller, Method, Model, State, Tolerances};

/// R(z) from the tableau: the stability polynomial the stability explorer reads.
pub(crate) fn tableau_polynomial() -> Vec<f64> {
    super::polynomial_from_tableau(&A, &B)
}

/// Tsit5, the explicit Runge–Kutta pair of order 5(4) by Tsitouras (2011): seven stages,
///
/// kᵢ = f(tₙ + cᵢh, yₙ + h·Σⱼ aᵢⱼkⱼ), yₙ₊₁ = yₙ + h·Σᵢ bᵢkᵢ,
///
/// with the error estimate yₙ₊₁ − ŷₙ₊₁ = h·Σᵢ (bᵢ − b̂ᵢ)kᵢ of the embedded order-4 solution. The
/// seventh stage is f(tₙ₊₁, yₙ₊₁) (first same as last), so an accepted step costs six new
/// evaluations. The dense output y(tₙ + θh) = yₙ + h·Σᵢ bᵢ(θ)kᵢ is of order 4 and needs no extra
/// evaluation. Coefficients: `tableaux/tsit5.rs`, checked by `scripts/check_tableaux.py`.
///
/// - **Order** 5 (4 for the estimate and the interpolant). Its coefficients were chosen to
///   minimise the fifth-order error terms rather than to satisfy the usual simplifying
///   assumptions, which makes it more efficient than Dormand–Prince 5(4) on most problems.
/// - **Step-size control**: Hairer's DOPRI5 controller for an order-4 estimate by default
///   ([`crate::Controller::dopri5`]).
/// - **Energy**: not symplectic; the drift is set by the tolerance.
/// - **Stability**: explicit; its stability region reaches about −3.5 on the real axis, so stiff
///   problems force tiny steps (they end in [`crate::Error::MaxSteps`], not a hang).
///
/// Reference: Ch. Tsitouras, "Runge–Kutta pairs of order 5(4) satisfying only the first column
/// simplifying assumption", Computers & Mathematics with Applications 62 (2011) 770–775.
pub type Tsit5<S> = ExplicitRk<S, Tsit5Tableau, STAGES>;

/// The coefficients of [`Tsit5`]: `tableaux/tsit5.rs`.
#[derive(Clone, Copy, Debug)]
pub struct Tsit5Tableau;

impl crate::integrators::sealed::Sealed for Tsit5Tableau {}

impl Tableau for Tsit5Tableau {
    const METHOD: Method = Method::Tsit5;
    const CONTROLLER: Controller = Controller::dopri5(4);
    const DENSE_DEGREE: usize = 4;
    /// Row 7 of A is b: the seventh stage is f(tₙ₊₁, yₙ₊₁), the FSAL stage.
    const STAGES: usize = STAGES - 1;
    const ESTIMATE_READS_LAST: bool = true;

    #[inline(always)]
    fn a(i: usize) -> &'static [f64] {
        &A[i][..i]
    }

    #[inline(always)]
    fn b() -> &'static [f64] {
        &B[..STAGES - 1]
    }

    #[inline(always)]
    fn c(i: usize) -> f64 {
        C[i]
    }

    /// yₙ₊₁ − ŷₙ₊₁ = h·Σᵢ (bᵢ − b̂ᵢ)kᵢ over all seven stages.
    #[inline(always)]
    fn error<S: State>(h: f64, k: &[S], y: &S, y_new: &S, tolerances: &Tolerances) -> f64 {
        let k = &k[..STAGES];
        tolerances.norm_of(
            |i| h * weighted(&BTILDE, k, i),
            y.as_slice(),
            y_new.as_slice(),
        )
    }

    /// y(tₙ + θh) = yₙ + Σₘ θᵐ⁺¹·(h·Σᵢ rᵢₘkᵢ): the interpolant's b_i(θ) regrouped by powers of θ.
    fn dense<M: Model>(
        _: &M,
        s: Step<'_, M::State>,
        _: &M::State,
        k: &mut [M::State],
        _: &mut M::State,
        dense: &mut DenseStep<M::State>,
    ) {
        let c = dense.fill(s.t, s.h, 4);
        c[0].clone_from(s.y);
        for (m, cm) in c[1..].iter_mut().enumerate() {
            let out = cm.as_mut_slice();
            out.fill(0.0);
            for (r, ki) in DENSE.iter().zip(&*k) {
                if r[m] != 0.0 {
                    axpy(out, s.h * r[m], ki.as_slice());
                }
            }
        }
    }
}
