//! Tsit5: Tsitouras' 5(4) Runge–Kutta pair with its free order-4 interpolant.

use super::tableaux::tsit5::{A, B, BTILDE, C, DENSE, STAGES};
use super::{Integrator, Step, axpy, copies, stage, weighted};
use super::DenseStep;
use crate::{Controller, Method, Model, NewtonOptions, Result, State, Stats};

/// R(z) from the tableau: the stability polynomial the stability explorer reads.
pub(crate) fn stability_polynomial() -> Vec<f64> {
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
#[derive(Clone, Debug)]
pub struct Tsit5<S> {
    /// k₁ … k₇ of the last attempt; after an accepted step k₇ = f(tₙ₊₁, yₙ₊₁).
    k: [S; STAGES],
    /// Stage inputs, then the error vector.
    probe: S,
    /// Whether k₁ already holds f at the start of the next attempt.
    have_k1: bool,
    /// Whether the last attempt was accepted, so its k₇ is the next step's k₁.
    fsal: bool,
}

impl<M: Model> Integrator<M> for Tsit5<M::State> {
    const METHOD: Method = Method::Tsit5;
    const CONTROLLER: Controller = Controller::dopri5(4);
    const DENSE_DEGREE: usize = 4;

    fn prepare(_: &M, _: f64, y0: &M::State, _: &NewtonOptions, _: &mut Stats) -> Result<Self> {
        Ok(Tsit5 {
            k: copies(y0)?,
            probe: y0.try_clone()?,
            have_k1: false,
            fsal: false,
        })
    }

    #[inline]
    fn duplicate(&self) -> Option<Self> {
        Some(self.clone())
    }

    fn attempt(&mut self, model: &M, s: Step<'_, M::State>, y_new: &mut M::State) -> Result<f64> {
        let (t, h, y) = (s.t, s.h, s.y);
        if self.fsal {
            self.k.swap(0, STAGES - 1);
            self.fsal = false;
        } else if !self.have_k1 {
            model.derivative(t, y, &mut self.k[0]);
            s.stats.evaluations += 1;
        }
        self.have_k1 = true;
        for i in 1..STAGES - 1 {
            let (done, rest) = self.k.split_at_mut(i);
            stage(&mut self.probe, y, h, &A[i][..i], done);
            model.derivative(t + C[i] * h, &self.probe, &mut rest[0]);
        }
        // Row 7 of A is b: the last stage input is yₙ₊₁ itself.
        stage(y_new, y, h, &B[..STAGES - 1], &self.k[..STAGES - 1]);
        model.derivative(t + h, y_new, &mut self.k[STAGES - 1]);
        s.stats.evaluations += STAGES as u64 - 1;
        let Some(tolerances) = s.tolerances else {
            return Ok(0.0);
        };
        let k = &self.k;
        Ok(tolerances.norm_of(
            |i| h * weighted(&BTILDE, k, i),
            y.as_slice(),
            y_new.as_slice(),
        ))
    }

    #[inline]
    fn accept(&mut self) {
        self.fsal = true;
    }

    fn restart(&mut self, _: &M, _: f64, _: &M::State, _: &mut Stats) {
        self.fsal = false;
        self.have_k1 = false;
    }

    /// y(tₙ + θh) = yₙ + Σₘ θᵐ⁺¹·(h·Σᵢ rᵢₘkᵢ): the interpolant's b_i(θ) regrouped by powers of θ.
    fn dense(
        &mut self,
        _: &M,
        s: Step<'_, M::State>,
        _: &M::State,
        dense: &mut DenseStep<M::State>,
    ) -> bool {
        let c = dense.fill(s.t, s.h, 4);
        c[0].clone_from(s.y);
        for (m, cm) in c[1..].iter_mut().enumerate() {
            let out = cm.as_mut_slice();
            out.fill(0.0);
            for (r, ki) in DENSE.iter().zip(&self.k) {
                if r[m] != 0.0 {
                    axpy(out, s.h * r[m], ki.as_slice());
                }
            }
        }
        true
    }
}
