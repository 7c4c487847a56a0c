//! The classical fourth-order Runge–Kutta method.

use super::{Integrator, Step, copies, set_axpy};
use crate::{Method, Model, NewtonOptions, Result, State, Stats};

/// R(z) = 1 + z + z²/2 + z³/6 + z⁴/24 (the Taylor polynomial of eᶻ): the stability
/// polynomial the stability explorer reads.
pub(crate) fn tableau_polynomial() -> Vec<f64> {
    vec![1.0, 1.0, 0.5, 1.0 / 6.0, 1.0 / 24.0]
}

/// Classical Runge–Kutta: k₁ = f(tₙ, yₙ), k₂ = f(tₙ + h/2, yₙ + h/2·k₁),
/// k₃ = f(tₙ + h/2, yₙ + h/2·k₂), k₄ = f(tₙ + h, yₙ + h·k₃),
/// yₙ₊₁ = yₙ + h/6·(k₁ + 2k₂ + 2k₃ + k₄).
///
/// - **Order** 4, four evaluations per step.
/// - **Energy**: not symplectic; on an undamped oscillator |R(iωh)|² = 1 − (ωh)⁶/72 + (ωh)⁸/576,
///   a slow secular decay.
/// - **Stability**: ωh < 2√2 on an undamped oscillator.
///
/// Reference: W. Kutta, Z. Math. Phys. 46 (1901) 435; Hairer, Nørsett & Wanner, *Solving
/// Ordinary Differential Equations I*, 2nd ed., 1993, §II.1.
#[derive(Clone, Debug)]
pub struct Rk4<S> {
    k: [S; 4],
    probe: S,
}

impl<S> crate::integrators::sealed::Sealed for Rk4<S> {}

impl<M: Model> Integrator<M> for Rk4<M::State> {
    const METHOD: Method = Method::Rk4;

    fn prepare(_: &M, _: f64, y0: &M::State, _: &NewtonOptions, _: &mut Stats) -> Result<Self> {
        Ok(Rk4 {
            k: copies(y0)?,
            probe: y0.try_clone()?,
        })
    }

    #[inline]
    fn duplicate(&self) -> Option<Self> {
        Some(self.clone())
    }

    #[inline]
    fn attempt(&mut self, model: &M, s: Step<'_, M::State>, y_new: &mut M::State) -> Result<f64> {
        let (t, h, y) = (s.t, s.h, s.y);
        let [k1, k2, k3, k4] = &mut self.k;
        let probe = &mut self.probe;
        model.derivative(t, y, k1);
        set_axpy(probe.as_mut_slice(), y.as_slice(), 0.5 * h, k1.as_slice());
        model.derivative(t + 0.5 * h, probe, k2);
        set_axpy(probe.as_mut_slice(), y.as_slice(), 0.5 * h, k2.as_slice());
        model.derivative(t + 0.5 * h, probe, k3);
        set_axpy(probe.as_mut_slice(), y.as_slice(), h, k3.as_slice());
        model.derivative(t + h, probe, k4);
        s.stats.evaluations += 4;
        let sixth = h / 6.0;
        let ks = k1
            .as_slice()
            .iter()
            .zip(k2.as_slice())
            .zip(k3.as_slice())
            .zip(k4.as_slice());
        let out = y_new.as_mut_slice().iter_mut().zip(y.as_slice());
        for ((o, yi), (((a, b), c), d)) in out.zip(ks) {
            *o = yi + sixth * (a + 2.0 * b + 2.0 * c + d);
        }
        Ok(0.0)
    }
}
