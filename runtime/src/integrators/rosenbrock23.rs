//! Rosenbrock23: the modified Rosenbrock method of MATLAB's `ode23s`.

use super::linearization::Linearization;
use super::rosenbrock::{Rosenbrock, RosenbrockTableau};
use super::{DenseStep, Step, axpy, set_axpy};
use crate::{Controller, Jacobian, Method, Result, State};

/// d = 1/(2 + √2), the method's one coefficient (correctly rounded; `1 − 1/√2` in `f64` is one
/// unit in the last place lower).
const D: f64 = 0.292_893_218_813_452_5;
/// e₃₂ = 6 + √2.
const E32: f64 = 7.414_213_562_373_095;
/// 1/(1 − 2d) = 1 + √2, the interpolant's scale.
const INTERPOLANT: f64 = 2.414_213_562_373_095;

/// Rosenbrock23, the linearly implicit method of Shampine & Reichelt behind MATLAB's `ode23s`.
/// With W = I − h·d·J, J = ∂f/∂y and T = ∂f/∂t at (tₙ, yₙ):
///
/// ```text
/// k₁ = W⁻¹(f(tₙ, yₙ) + h·d·T)
/// k₂ = W⁻¹(f(tₙ + h/2, yₙ + h/2·k₁) − k₁) + k₁
/// yₙ₊₁ = yₙ + h·k₂                                              (order 2)
/// k₃ = W⁻¹(f(tₙ₊₁, yₙ₊₁) − e₃₂(k₂ − F₁) − 2(k₁ − F₀) + h·d·T)
/// err = h/6·(k₁ − 2k₂ + k₃)                                      (order-3 estimate)
/// ```
///
/// One Jacobian, one ∂f/∂t (only for models that read the time), one factorization and three
/// solves a step; f(tₙ₊₁, yₙ₊₁) is the next step's f(tₙ, yₙ) (first same as last), so two new
/// evaluations of f. A rejected step keeps J and ∂f/∂t and only refactorizes W for its new h.
/// The dense output yₙ + h·[θ(1 − θ)k₁ + θ(θ − 2d)k₂]/(1 − 2d) is of order 2.
///
/// With a mass matrix (M·y′ = f, a differential–algebraic model), W = M − h·d·J and the k's,
/// which are rates, enter the right-hand sides through M: F₁ − M·k₁ and
/// F₂ − M(e₃₂k₂ + 2k₁) + e₃₂F₁ + 2F₀ (as OrdinaryDiffEq.jl's mass-matrix form).
///
/// - **Order** 2, with an order-3 error estimate; for loose tolerances (rtol 1e-2 … 1e-5),
///   where it takes fewer, cheaper steps than higher-order methods.
/// - **Stability**: L-stable, R(∞) = 0; its error estimate is exact for any J (a W-method, so
///   an approximate Jacobian costs accuracy, not order).
/// - **Step-size control**: `ode23s`'s own constants ([`Controller::rosenbrock23`]).
///
/// Reference: L. F. Shampine, M. W. Reichelt, "The MATLAB ODE Suite", SIAM J. Sci. Comput. 18
/// (1997) 1–22, §3.1; the formulas as in MATLAB's `ode23s.m` and `ntrp23s.m` (checked by
/// `scripts/check_rosenbrock.py`).
pub type Rosenbrock23<M> = Rosenbrock<M, Rosenbrock23Tableau, 6>;

/// The formulas of [`Rosenbrock23`]. Its work vectors are k₁, k₂, k₃, F₁, F₂ = f(tₙ₊₁, yₙ₊₁)
/// (the next step's F₀) and a scratch vector (the stage input, then the error).
#[derive(Clone, Copy, Debug)]
pub struct Rosenbrock23Tableau;

impl crate::integrators::sealed::Sealed for Rosenbrock23Tableau {}

impl RosenbrockTableau for Rosenbrock23Tableau {
    const METHOD: Method = Method::Rosenbrock23;
    const CONTROLLER: Controller = Controller::rosenbrock23();
    const DENSE_DEGREE: usize = 2;
    const GAMMA: f64 = D;
    const FSAL: Option<usize> = Some(4);

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
        let hd = h * D;
        let time = M::TIME_DEPENDENT;
        let [k1, k2, k3, f1, f2, probe] = work else {
            unreachable!("Rosenbrock23 has 6 work vectors")
        };
        // k₁ = W⁻¹(F₀ + h·d·T)
        k1.clone_from(f0);
        if time {
            axpy(k1.as_mut_slice(), hd, linear.dfdt.as_slice());
        }
        linear.solve(k1.as_mut_slice(), t, h, s.stats)?;
        // F₁ = f(t + h/2, y + h/2·k₁); k₂ = W⁻¹(F₁ − k₁) + k₁
        set_axpy(probe.as_mut_slice(), y.as_slice(), 0.5 * h, k1.as_slice());
        model.derivative(t + 0.5 * h, probe, f1);
        if M::MASS_MATRIX {
            k2.clone_from(f1);
            linear.mass_add(k2.as_mut_slice(), -1.0, k1.as_slice());
        } else {
            set_axpy(k2.as_mut_slice(), f1.as_slice(), -1.0, k1.as_slice());
        }
        linear.solve(k2.as_mut_slice(), t, h, s.stats)?;
        axpy(k2.as_mut_slice(), 1.0, k1.as_slice());
        set_axpy(y_new.as_mut_slice(), y.as_slice(), h, k2.as_slice());
        // F₂ = f(tₙ₊₁, yₙ₊₁), the next step's F₀.
        model.derivative(t + h, y_new, f2);
        s.stats.evaluations += 2;
        let Some(tolerances) = s.tolerances else {
            return Ok(0.0);
        };
        // k₃ = W⁻¹(F₂ − e₃₂(k₂ − F₁) − 2(k₁ − F₀) + h·d·T)
        if M::MASS_MATRIX {
            // F₂ + e₃₂F₁ + 2F₀ − M(e₃₂k₂ + 2k₁): the k's are rates, which M weighs.
            let parts = f2.as_slice().iter().zip(f1.as_slice()).zip(f0.as_slice());
            for (o, ((f2i, f1i), f0i)) in k3.as_mut_slice().iter_mut().zip(parts) {
                *o = f2i + E32 * f1i + 2.0 * f0i;
            }
            let sum = probe.as_mut_slice();
            for (o, (k2i, k1i)) in sum.iter_mut().zip(k2.as_slice().iter().zip(k1.as_slice())) {
                *o = E32 * k2i + 2.0 * k1i;
            }
            linear.mass_add(k3.as_mut_slice(), -1.0, probe.as_slice());
        } else {
            let parts = (f2.as_slice().iter().zip(k2.as_slice()).zip(f1.as_slice()))
                .zip(k1.as_slice().iter().zip(f0.as_slice()));
            for (o, (((f2i, k2i), f1i), (k1i, f0i))) in k3.as_mut_slice().iter_mut().zip(parts) {
                *o = f2i - E32 * (k2i - f1i) - 2.0 * (k1i - f0i);
            }
        }
        if time {
            axpy(k3.as_mut_slice(), hd, linear.dfdt.as_slice());
        }
        linear.solve(k3.as_mut_slice(), t, h, s.stats)?;
        // err = h/6·(k₁ − 2k₂ + k₃)
        let e = probe.as_mut_slice();
        for (o, ((a, b), c)) in e
            .iter_mut()
            .zip(k1.as_slice().iter().zip(k2.as_slice()).zip(k3.as_slice()))
        {
            *o = h / 6.0 * (a - 2.0 * b + c);
        }
        Ok(tolerances.norm(e, y.as_slice(), y_new.as_slice()))
    }

    /// yₙ + θ·h(k₁ − 2d·k₂)/(1 − 2d) + θ²·h(k₂ − k₁)/(1 − 2d).
    fn dense<S: State>(s: Step<'_, S>, _: &S, work: &[S], dense: &mut DenseStep<S>) {
        let [k1, k2, ..] = work else {
            unreachable!("Rosenbrock23 has 6 work vectors")
        };
        let [c0, c1, c2] = dense.fill(s.t, s.h, 2) else {
            unreachable!("fill returns degree + 1 coefficients")
        };
        c0.clone_from(s.y);
        let scale = s.h * INTERPOLANT;
        for ((o1, o2), (a, b)) in c1
            .as_mut_slice()
            .iter_mut()
            .zip(c2.as_mut_slice())
            .zip(k1.as_slice().iter().zip(k2.as_slice()))
        {
            *o1 = scale * (a - 2.0 * D * b);
            *o2 = scale * (b - a);
        }
    }
}
