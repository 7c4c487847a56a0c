//! DOP853: Dormand and Prince's order-8 Runge–Kutta method with Hairer's 8(5,3) error estimate.

use super::tableaux::dop853::{A, A_EXTRA, B, C, C_EXTRA, D, E3, E5, STAGES};
use super::{Integrator, Step, copies, stage, weighted};
use super::DenseStep;
use crate::{Controller, Method, Model, NewtonOptions, Result, State, Stats};

/// Stages kept: the 12 of the step, k₁₃ = f(tₙ₊₁, yₙ₊₁), and the 3 of the dense output.
const KEPT: usize = 16;

/// R(z) from the tableau: the stability polynomial the stability explorer reads.
pub(crate) fn stability_polynomial() -> Vec<f64> {
    super::polynomial_from_tableau(&A, &B)
}

/// DOP853, the explicit Runge–Kutta method of order 8 of Dormand & Prince (1980) with the error
/// estimate and dense output of Hairer's code DOP853:
///
/// kᵢ = f(tₙ + cᵢh, yₙ + h·Σⱼ aᵢⱼkⱼ) for i = 1 … 12, yₙ₊₁ = yₙ + h·Σᵢ bᵢkᵢ.
///
/// The error combines an order-5 estimate e₅ = h·Σ E5ᵢkᵢ and an order-3 one e₃ = h·Σ E3ᵢkᵢ as
/// err = ‖e₅‖²/√(‖e₅‖² + 0.01·‖e₃‖²) in the tolerance-weighted RMS norm: O(h⁸), reliable at
/// large steps where e₅ alone can vanish by accident. An attempt costs 11 evaluations; as in
/// Hairer's code, k₁₃ = f(tₙ₊₁, yₙ₊₁) is evaluated only once the step is accepted (it is the
/// next step's k₁), so a rejected step wastes no evaluation on it. The dense output of order 7
/// needs k₁₃ and three more stages (14–16), made only when the driver asks for it.
/// Coefficients: `tableaux/dop853.rs`, checked by `scripts/check_tableaux.py`.
///
/// - **Order** 8 (dense output 7).
/// - **Step-size control**: Hairer's DOP853 defaults ([`crate::Controller::dop853`]).
/// - **Energy**: not symplectic; the drift is set by the tolerance, and at tight tolerances it
///   is usually below that of the symplectic methods at equal cost.
/// - **Stability**: explicit (real stability boundary about −6); not for stiff problems.
///
/// Reference: E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*,
/// 2nd ed., Springer 1993, §II.5, §II.6 and §II.10 (the code DOP853); J. R. Dormand,
/// P. J. Prince, "A family of embedded Runge–Kutta formulae", J. Comp. Appl. Math. 6 (1980) 19.
#[derive(Clone, Debug)]
pub struct Dop853<S> {
    /// k₁ … k₁₆ (0-based); `k[12]` = f(tₙ₊₁, yₙ₊₁) once the dense output needed it.
    k: [S; KEPT],
    probe: S,
    /// Whether k₁ holds f at the start of the next attempt.
    have_k1: bool,
    /// Whether `k[12]` holds f at the end of the accepted step, the next step's k₁.
    fsal: bool,
}

impl<M: Model> Integrator<M> for Dop853<M::State> {
    const METHOD: Method = Method::Dop853;
    const CONTROLLER: Controller = Controller::dop853();
    const DENSE_DEGREE: usize = 7;

    fn prepare(_: &M, _: f64, y0: &M::State, _: &NewtonOptions, _: &mut Stats) -> Result<Self> {
        Ok(Dop853 {
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
            self.k.swap(0, STAGES);
            self.fsal = false;
        } else if !self.have_k1 {
            model.derivative(t, y, &mut self.k[0]);
            s.stats.evaluations += 1;
        }
        self.have_k1 = true;
        for i in 1..STAGES {
            let (done, rest) = self.k.split_at_mut(i);
            stage(&mut self.probe, y, h, &A[i][..i], done);
            model.derivative(t + C[i] * h, &self.probe, &mut rest[0]);
        }
        stage(y_new, y, h, &B, &self.k[..STAGES]);
        s.stats.evaluations += STAGES as u64 - 1;
        let Some(tolerances) = s.tolerances else {
            return Ok(0.0);
        };
        let (y, z) = (y.as_slice(), y_new.as_slice());
        let (mut err5, mut err3) = (0.0, 0.0);
        for i in 0..y.len() {
            let sk = tolerances.scale(i, y[i], z[i]);
            let e5 = weighted(&E5, &self.k, i) / sk;
            let e3 = weighted(&E3, &self.k, i) / sk;
            err5 += e5 * e5;
            err3 += e3 * e3;
        }
        let denominator = err5 + 0.01 * err3;
        let denominator = if denominator > 0.0 { denominator } else { 1.0 };
        Ok(h.abs() * err5 / (y.len() as f64 * denominator).sqrt())
    }

    #[inline]
    fn accept(&mut self) {
        // k₁₃ is made by the next attempt, or by `dense` if the driver asks for it first.
        self.have_k1 = false;
    }

    fn restart(&mut self, _: &M, _: f64, _: &M::State, _: &mut Stats) {
        self.fsal = false;
        self.have_k1 = false;
    }

    /// Hairer's CONTD8 polynomial, r₀ + θ(r₁ + θ₁(r₂ + θ(r₃ + θ₁(r₄ + θ(r₅ + θ₁(r₆ + θr₇)))))) with
    /// θ₁ = 1 − θ, expanded into powers of θ after the three extra stages.
    fn dense(
        &mut self,
        model: &M,
        s: Step<'_, M::State>,
        y_new: &M::State,
        dense: &mut DenseStep<M::State>,
    ) -> bool {
        let (t, h, y) = (s.t, s.h, s.y);
        if !self.fsal {
            model.derivative(t + h, y_new, &mut self.k[STAGES]);
            s.stats.evaluations += 1;
            self.fsal = true;
        }
        for (r, (ar, cr)) in A_EXTRA.iter().zip(C_EXTRA).enumerate() {
            let i = STAGES + 1 + r;
            let (done, rest) = self.k.split_at_mut(i);
            stage(&mut self.probe, y, h, &ar[..i], done);
            model.derivative(t + cr * h, &self.probe, &mut rest[0]);
        }
        s.stats.evaluations += 3;
        let coefficients = dense.fill(t, h, 7);
        for m in 0..y.as_slice().len() {
            let (y0, y1) = (y.as_slice()[m], y_new.as_slice()[m]);
            let r1 = y1 - y0;
            let r2 = h * self.k[0].as_slice()[m] - r1;
            let r3 = r1 - h * self.k[STAGES].as_slice()[m] - r2;
            let d = |row: &[f64; 16]| {
                h * row
                    .iter()
                    .zip(&self.k)
                    .map(|(dj, kj)| dj * kj.as_slice()[m])
                    .sum::<f64>()
            };
            let r = [y0, r1, r2, r3, d(&D[0]), d(&D[1]), d(&D[2]), d(&D[3])];
            // Expand from the inside: P ← r₇; then P ← rⱼ + θ·P or rⱼ + (1 − θ)·P alternately.
            let mut p = [0.0; 8];
            p[0] = r[7];
            for j in (0..7).rev() {
                let by_theta = j % 2 == 0;
                for i in (0..7).rev() {
                    p[i + 1] = if by_theta { p[i] } else { p[i + 1] - p[i] };
                }
                if by_theta {
                    p[0] = 0.0;
                }
                p[0] += r[j];
            }
            for (c, pi) in coefficients.iter_mut().zip(p) {
                c.as_mut_slice()[m] = pi;
            }
        }
        true
    }
}
