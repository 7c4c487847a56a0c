//! DOP853: Dormand and Prince's order-8 Runge–Kutta method with Hairer's 8(5,3) error estimate.

use super::explicit_rk::{ExplicitRk, Tableau, combine, weighted};
use super::tableaux::dop853::{A, A_EXTRA, B, C, C_EXTRA, D, E3, E5, STAGES};
use super::{DenseStep, Step};
use crate::{Controller, Method, Model, State, Tolerances};

/// Stages kept: the 12 of the step, k₁₃ = f(tₙ₊₁, yₙ₊₁), and the 3 of the dense output.
const KEPT: usize = 16;

/// R(z) from the tableau: the stability polynomial the stability explorer reads.
pub(crate) fn tableau_polynomial() -> Vec<f64> {
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
pub type Dop853<S> = ExplicitRk<S, Dop853Tableau, KEPT>;

/// Component i of the order-5 and order-3 estimates, without the factor h, over `scale`.
#[inline(always)]
fn estimates<S: State>(k: &[S], i: usize, scale: f64) -> (f64, f64) {
    (weighted(&E5, k, i) / scale, weighted(&E3, k, i) / scale)
}

/// err = |h|·ERR/√(N·DENO), DENO = ERR + 0.01·ERR2 (1 if that is 0), from ERR = Σ e₅ᵢ² and
/// ERR2 = Σ e₃ᵢ² over the N components.
#[inline(always)]
fn combined(h: f64, err5: f64, err3: f64, n: usize) -> f64 {
    let denominator = err5 + 0.01 * err3;
    let denominator = if denominator > 0.0 { denominator } else { 1.0 };
    h.abs() * err5 / (n as f64 * denominator).sqrt()
}

/// The coefficients, error estimate and dense output of [`Dop853`]: `tableaux/dop853.rs`.
#[derive(Clone, Copy, Debug)]
pub struct Dop853Tableau;

impl crate::integrators::sealed::Sealed for Dop853Tableau {}

impl Tableau for Dop853Tableau {
    const METHOD: Method = Method::Dop853;
    const CONTROLLER: Controller = Controller::dop853();
    const DENSE_DEGREE: usize = 7;
    const STAGES: usize = STAGES;
    const ESTIMATE_READS_LAST: bool = false;

    #[inline(always)]
    fn a(i: usize) -> &'static [f64] {
        &A[i][..i]
    }

    #[inline(always)]
    fn b() -> &'static [f64] {
        &B
    }

    #[inline(always)]
    fn c(i: usize) -> f64 {
        C[i]
    }

    /// err = ‖e₅‖²/√(‖e₅‖² + 0.01·‖e₃‖²), as DP86CO computes it.
    #[inline(always)]
    fn error<S: State>(h: f64, k: &[S], y: &S, y_new: &S, tolerances: &Tolerances) -> f64 {
        let (mut err5, mut err3) = (0.0, 0.0);
        for (i, (y0, y1)) in y.as_slice().iter().zip(y_new.as_slice()).enumerate() {
            let (e5, e3) = estimates(k, i, tolerances.scale(i, *y0, *y1));
            err5 += e5 * e5;
            err3 += e3 * e3;
        }
        combined(h, err5, err3, tolerances.controlled(y.as_slice().len()))
    }

    /// Hairer's CONTD8 polynomial, r₀ + θ(r₁ + θ₁(r₂ + θ(r₃ + θ₁(r₄ + θ(r₅ + θ₁(r₆ + θr₇)))))) with
    /// θ₁ = 1 − θ, expanded into powers of θ after the three extra stages.
    fn dense<M: Model>(
        model: &M,
        s: Step<'_, M::State>,
        y_new: &M::State,
        k: &mut [M::State],
        probe: &mut M::State,
        dense: &mut DenseStep<M::State>,
    ) {
        let (t, h, y) = (s.t, s.h, s.y);
        extra_stage::<M, 0>(model, t, h, y, k, probe);
        extra_stage::<M, 1>(model, t, h, y, k, probe);
        extra_stage::<M, 2>(model, t, h, y, k, probe);
        s.stats.evaluations += 3;
        let coefficients = dense.fill(t, h, 7);
        for m in 0..y.as_slice().len() {
            let (y0, y1) = (y.as_slice()[m], y_new.as_slice()[m]);
            let r1 = y1 - y0;
            let r2 = h * k[0].as_slice()[m] - r1;
            let r3 = r1 - h * k[STAGES].as_slice()[m] - r2;
            let d = |row: &[f64; KEPT]| {
                h * row
                    .iter()
                    .zip(&*k)
                    .map(|(dj, kj)| dj * kj.as_slice()[m])
                    .sum::<f64>()
            };
            let r = [y0, r1, r2, r3, d(&D[0]), d(&D[1]), d(&D[2]), d(&D[3])];
            // Expand from the inside: P ← r₇; then P ← rⱼ + θ·P or rⱼ + (1 − θ)·P alternately,
            // in θ's monomials. Written out on values, not as a loop over a stack array: the
            // loop kept P in memory and made each update wait on the previous store (6.7 µs a
            // step of 28 components, three times the step itself; perf on the Pleiades).
            let theta = |p: [f64; 8], rj: f64| [0.0 + rj, p[0], p[1], p[2], p[3], p[4], p[5], p[6]];
            let one_minus_theta = |p: [f64; 8], rj: f64| {
                [
                    p[0] + rj,
                    p[1] - p[0],
                    p[2] - p[1],
                    p[3] - p[2],
                    p[4] - p[3],
                    p[5] - p[4],
                    p[6] - p[5],
                    p[7] - p[6],
                ]
            };
            let p = [r[7], 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
            let p = theta(p, r[6]);
            let p = one_minus_theta(p, r[5]);
            let p = theta(p, r[4]);
            let p = one_minus_theta(p, r[3]);
            let p = theta(p, r[2]);
            let p = one_minus_theta(p, r[1]);
            let p = theta(p, r[0]);
            for (c, pi) in coefficients.iter_mut().zip(p) {
                c.as_mut_slice()[m] = pi;
            }
        }
    }
}

/// The dense output's extra stage `R`, k_{s+2+R}, one function per stage like the step's (so its
/// coefficients are constants and its zeros drop out whatever LLVM inlines: written as a loop
/// over the three, the loop stayed rolled once the Pleiades' force was unrolled into it, and the
/// stage sums tested every coefficient at run time — 1.18–1.84 ms a run against 1.07–1.42 ms
/// before the force was unrolled and 0.89–1.06 ms now, `generated_vs_hand --
/// pleiades::dop853_dense`, 2026-11-27).
#[inline(always)]
fn extra_stage<M: Model, const R: usize>(
    model: &M,
    t: f64,
    h: f64,
    y: &M::State,
    k: &mut [M::State],
    probe: &mut M::State,
) {
    let i = STAGES + 1 + R;
    let (done, rest) = k.split_at_mut(i);
    combine(probe, y, h, &A_EXTRA[R][..i], done);
    model.derivative(t + C_EXTRA[R] * h, probe, &mut rest[0]);
}
