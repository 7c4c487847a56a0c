//! Rodas5P: Steinebach's stiffly accurate Rosenbrock–Wanner method of order 5(4).

use super::linearization::Linearization;
use super::rosenbrock::{Rosenbrock, RosenbrockTableau};
use super::tableaux::rodas5p::{A, C, COUPLING, D, GAMMA, H, STAGES};
use super::{DenseStep, Step, axpy};
use crate::{Controller, Jacobian, Method, Result, State};

/// Rodas5P, the Rosenbrock–Wanner method of order 5 of Steinebach (2023), in the W-transformed
/// form of Hairer & Wanner (*Solving ODEs II*, §IV.7): with J = ∂f/∂y and T = ∂f/∂t at (tₙ, yₙ)
/// and one matrix W = I − γh·J for all eight stages,
///
/// ```text
/// Uᵢ = yₙ + Σⱼ aᵢⱼ uⱼ
/// W uᵢ = γh·( f(tₙ + cᵢh, Uᵢ) + Σⱼ (Cᵢⱼ/h) uⱼ + h dᵢ T )        i = 1 … 8
/// yₙ₊₁ = U₈ + u₈,   err = u₈
/// ```
///
/// Stiffly accurate (the last stages are the solution itself), so it keeps its order on stiff
/// problems and differential-algebraic limits where other Rosenbrock methods lose it.
///
/// **Differential–algebraic models**, M·y′ = f(t, y) with M constant and possibly singular
/// (`#[algebraic]` fields, `fn mass`): W = M − γh·J and the coupling term is M·Σⱼ (Cᵢⱼ/h) uⱼ
/// (Hairer & Wanner, *Solving ODEs II*, §VI.4). The coefficients are those Steinebach
/// derived for index-1 DAEs: like Rodas5's they satisfy the DAE order conditions to order 5
/// (4 for the embedded estimate), and they were chosen with the Prothero–Robinson model in view,
/// for an order that holds on stiff and algebraic components alike (measured: 4.96 on the
/// Cartesian pendulum, its algebraic λ included, `tests/models/dae/`). A solve with a singular M is no
/// different: W is regular wherever ∂g/∂z is (index 1).
///
/// The dense output (1 − θ)yₙ + θ(yₙ₊₁ + (1 − θ)(K₁ + θ(K₂ + θK₃))), Kᵣ = Σⱼ Hᵣⱼuⱼ, is of order 4 and free.
/// One Jacobian, one ∂f/∂t (only when the model reads the time), one factorization, eight
/// solves and eight evaluations of f a step (seven when a rejected step is retried: f(tₙ, yₙ),
/// J and T are kept, W is refactorized for the new h). Coefficients: `tableaux/rodas5p.rs`,
/// checked by `scripts/check_rosenbrock.py`.
///
/// - **Order** 5 (4 for the estimate and the dense output); 2 if J is not the exact Jacobian,
///   which `#[system]` guarantees it is.
/// - **Stability**: L-stable, R(∞) = 0: stiff components are damped in one step at any h.
/// - **Step-size control**: the PI controller for an order-4 estimate
///   ([`Controller::dopri5`]).
///
/// Reference: G. Steinebach, "Construction of Rosenbrock–Wanner method Rodas5P and numerical
/// benchmarks within the Julia Differential Equations package", BIT Numer. Math. 63 (2023) 27.
pub type Rodas5P<M> = Rosenbrock<M, Rodas5PTableau, { STAGES + 2 }>;

/// The coefficients and stages of [`Rodas5P`]: `tableaux/rodas5p.rs`. Its work vectors are
/// u₁ … u₈, then Uᵢ and the right-hand side of stage i.
#[derive(Clone, Copy, Debug)]
pub struct Rodas5PTableau;

impl crate::integrators::sealed::Sealed for Rodas5PTableau {}

impl RosenbrockTableau for Rodas5PTableau {
    const METHOD: Method = Method::Rodas5P;
    const CONTROLLER: Controller = Controller::dopri5(4);
    const DENSE_DEGREE: usize = 4;
    const GAMMA: f64 = GAMMA;
    const FSAL: Option<usize> = None;

    #[inline(always)]
    fn stages<M: Jacobian>(
        model: &M,
        s: Step<'_, M::State>,
        linear: &mut Linearization<M>,
        f0: &M::State,
        work: &mut [M::State],
        y_new: &mut M::State,
    ) -> Result<f64> {
        let (t, h, y) = (s.t, s.h, s.y);
        let gh = GAMMA * h;
        let (u, rest) = work.split_at_mut(STAGES);
        let [stage, rhs] = rest else {
            unreachable!("Rodas5P has STAGES + 2 work vectors")
        };
        for i in 0..STAGES {
            let (done, rest) = u.split_at_mut(i);
            let input = stage.as_mut_slice();
            input.copy_from_slice(y.as_slice());
            for (a, uj) in A[i].iter().zip(done.iter()) {
                if *a != 0.0 {
                    axpy(input, *a, uj.as_slice());
                }
            }
            if i == 0 {
                rhs.clone_from(f0);
            } else {
                model.derivative(t + C[i] * h, stage, rhs);
                s.stats.evaluations += 1;
            }
            let b = rhs.as_mut_slice();
            if M::MASS_MATRIX {
                // M·Σⱼ (Cᵢⱼ/h) uⱼ, summed in uᵢ's slot, which the solve below fills.
                let sum = rest[0].as_mut_slice();
                sum.fill(0.0);
                for (coupling, uj) in COUPLING[i].iter().zip(done.iter()) {
                    if *coupling != 0.0 {
                        axpy(sum, coupling / h, uj.as_slice());
                    }
                }
                linear.mass_add(b, 1.0, sum);
            } else {
                for (coupling, uj) in COUPLING[i].iter().zip(done.iter()) {
                    if *coupling != 0.0 {
                        axpy(b, coupling / h, uj.as_slice());
                    }
                }
            }
            if M::TIME_DEPENDENT && D[i] != 0.0 {
                axpy(b, h * D[i], linear.dfdt.as_slice());
            }
            for r in b.iter_mut() {
                *r *= gh;
            }
            linear.solve(b, t, h, s.stats)?;
            rest[0].clone_from(rhs);
        }
        // Stiffly accurate: yₙ₊₁ = U₈ + u₈, and u₈ is the error estimate.
        let last = &u[STAGES - 1];
        for ((o, stage), ui) in y_new
            .as_mut_slice()
            .iter_mut()
            .zip(stage.as_slice())
            .zip(last.as_slice())
        {
            *o = stage + ui;
        }
        Ok(s.tolerances.map_or(0.0, |tol| {
            tol.norm(last.as_slice(), y.as_slice(), y_new.as_slice())
        }))
    }

    /// (1 − θ)yₙ + θyₙ₊₁ + θ(1 − θ)(K₁ + θK₂ + θ²K₃) in powers of θ:
    /// yₙ + θ(Δ + K₁) + θ²(K₂ − K₁) + θ³(K₃ − K₂) − θ⁴K₃, Δ = yₙ₊₁ − yₙ.
    fn dense<S: State>(s: Step<'_, S>, y_new: &S, work: &[S], dense: &mut DenseStep<S>) {
        let coefficients = dense.fill(s.t, s.h, 4);
        // K₁, K₂, K₃ into c₂, c₃, c₄ first.
        for (r, k) in coefficients[2..].iter_mut().enumerate() {
            let out = k.as_mut_slice();
            out.fill(0.0);
            for (hj, uj) in H[r].iter().zip(&work[..STAGES]) {
                if *hj != 0.0 {
                    axpy(out, *hj, uj.as_slice());
                }
            }
        }
        let (low, high) = coefficients.split_at_mut(2);
        let [c0, c1] = low else {
            unreachable!("fill returns degree + 1 coefficients")
        };
        let [c2, c3, c4] = high else {
            unreachable!("fill returns degree + 1 coefficients")
        };
        c0.clone_from(s.y);
        let parts = c1
            .as_mut_slice()
            .iter_mut()
            .zip(c2.as_mut_slice())
            .zip(c3.as_mut_slice())
            .zip(c4.as_mut_slice());
        for ((((o1, o2), o3), o4), (y0, y1)) in
            parts.zip(s.y.as_slice().iter().zip(y_new.as_slice()))
        {
            let (k1, k2, k3) = (*o2, *o3, *o4);
            *o1 = y1 - y0 + k1;
            *o2 = k2 - k1;
            *o3 = k3 - k2;
            *o4 = -k3;
        }
    }
}
