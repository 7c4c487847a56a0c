//! Explicit embedded Runge–Kutta pairs: the stage loop, the first-same-as-last reuse and the
//! dense output on demand that [`Tsit5`](super::Tsit5) and [`Dop853`](super::Dop853) share.

use std::fmt::Debug;
use std::marker::PhantomData;

use super::{DenseStep, Integrator, Step, copies};
use crate::{Controller, Method, Model, NewtonOptions, Result, State, Stats, Tolerances};

/// The coefficients of an explicit embedded pair and what differs between pairs: the error
/// estimate and the continuous extension.
///
/// One step of size h from (tₙ, yₙ) with s = [`STAGES`](Tableau::STAGES):
///
/// kᵢ = f(tₙ + cᵢh, yₙ + h·Σⱼ₍ⱼ₍ᵢ₎ aᵢⱼkⱼ) for i = 1 … s, yₙ₊₁ = yₙ + h·Σᵢ bᵢkᵢ,
///
/// and kₛ₊₁ = f(tₙ₊₁, yₙ₊₁) is the next step's k₁ (first same as last).
pub trait Tableau: Clone + Debug + super::Sealed {
    /// The method the tableau implements.
    const METHOD: Method;
    /// The step-size controller of adaptive runs.
    const CONTROLLER: Controller;
    /// Degree of the polynomial [`Tableau::dense`] fills.
    const DENSE_DEGREE: usize;
    /// s, the number of stages that make yₙ₊₁ (at most 16).
    const STAGES: usize;
    /// Whether the error estimate reads kₛ₊₁ = f(tₙ₊₁, yₙ₊₁), so every attempt evaluates it
    /// (Tsit5). Otherwise it is evaluated only after the step is accepted, by the next attempt
    /// or the dense output, so a rejected step wastes no evaluation on it (DOP853, as Hairer's
    /// code).
    const ESTIMATE_READS_LAST: bool;

    /// aᵢ₁ … aᵢ,ᵢ₋₁ (row i of A to the left of the diagonal, 0-based: `a(i).len() == i`), for
    /// 0 < i < s.
    fn a(i: usize) -> &'static [f64];
    /// b₁ … bₛ.
    fn b() -> &'static [f64];
    /// cᵢ (0-based), for i < s.
    fn c(i: usize) -> f64;

    /// The error norm of the step from `y` to `y_new` of size `h` against `tolerances`, from the
    /// stages k₁ … kₛ (and kₛ₊₁ when [`ESTIMATE_READS_LAST`](Tableau::ESTIMATE_READS_LAST)).
    fn error<S: State>(h: f64, k: &[S], y: &S, y_new: &S, tolerances: &Tolerances) -> f64;

    /// Fills `dense` for the accepted step from (t, y) to (t + h, `y_new`), given its stages
    /// k₁ … kₛ₊₁; `k` has room after them for extra stages, evaluated with `probe` as the stage
    /// input and counted in the step's `stats`.
    fn dense<M: Model>(
        model: &M,
        step: Step<'_, M::State>,
        y_new: &M::State,
        k: &mut [M::State],
        probe: &mut M::State,
        dense: &mut DenseStep<M::State>,
    );
}

/// An explicit embedded Runge–Kutta pair with the tableau `T`, keeping `K` stage vectors (the
/// s + 1 of a step and any that the dense output adds).
///
/// An attempt evaluates k₂ … kₛ, and kₛ₊₁ = f(tₙ₊₁, yₙ₊₁) in the attempt if the estimate reads
/// it, else once the step is accepted (by the next attempt as its k₁, or by the dense output):
/// an accepted step costs s evaluations of f, a rejected one s or s − 1, and its retry starts
/// from the kept k₁. The continuous extension is built only when the driver asks for it
/// (events, save times, a recorded dense output).
#[derive(Clone, Debug)]
pub struct ExplicitRk<S, T, const K: usize> {
    /// k₁ … k_K (0-based); after an accepted step `k[s]` = f(tₙ₊₁, yₙ₊₁) once it is made.
    k: [S; K],
    /// Stage inputs.
    probe: S,
    /// Whether k₁ already holds f at the start of the next attempt.
    have_k1: bool,
    /// Whether `k[s]` holds f at the end of the accepted step, the next attempt's k₁.
    fsal: bool,
    tableau: PhantomData<T>,
}

impl<S: State, T: Tableau, const K: usize> ExplicitRk<S, T, K> {
    /// Stage i (0 < i < s): kᵢ = f(tₙ + cᵢh, yₙ + h·Σⱼ aᵢⱼkⱼ).
    #[inline(always)]
    fn stage<M: Model<State = S>, const I: usize>(&mut self, model: &M, t: f64, h: f64, y: &S) {
        if I >= T::STAGES {
            return;
        }
        let (done, rest) = self.k.split_at_mut(I);
        combine(&mut self.probe, y, h, T::a(I), done);
        model.derivative(t + T::c(I) * h, &self.probe, &mut rest[0]);
    }
}

impl<S, T: Tableau, const K: usize> crate::integrators::sealed::Sealed for ExplicitRk<S, T, K> {}

impl<M: Model, T: Tableau, const K: usize> Integrator<M> for ExplicitRk<M::State, T, K> {
    const METHOD: Method = T::METHOD;
    const CONTROLLER: Controller = T::CONTROLLER;
    const DENSE_DEGREE: usize = T::DENSE_DEGREE;

    fn prepare(_: &M, _: f64, y0: &M::State, _: &NewtonOptions, _: &mut Stats) -> Result<Self> {
        const { assert!(T::STAGES < K && T::STAGES <= 16) };
        Ok(ExplicitRk {
            k: copies(y0)?,
            probe: y0.try_clone()?,
            have_k1: false,
            fsal: false,
            tableau: PhantomData,
        })
    }

    #[inline]
    fn duplicate(&self) -> Option<Self> {
        Some(self.clone())
    }

    fn attempt(&mut self, model: &M, s: Step<'_, M::State>, y_new: &mut M::State) -> Result<f64> {
        let (t, h, y) = (s.t, s.h, s.y);
        if self.fsal {
            self.k.swap(0, T::STAGES);
            self.fsal = false;
        } else if !self.have_k1 {
            model.derivative(t, y, &mut self.k[0]);
            s.stats.evaluations += 1;
        }
        self.have_k1 = true;
        // Unrolled, stage by stage, so each row's coefficients are constants and its zeros drop
        // out.
        macro_rules! stages {
            ($($i:literal)*) => { $( self.stage::<M, $i>(model, t, h, y); )* };
        }
        stages!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15);
        combine(y_new, y, h, T::b(), &self.k[..T::STAGES]);
        s.stats.evaluations += T::STAGES as u64 - 1;
        if T::ESTIMATE_READS_LAST {
            model.derivative(t + h, y_new, &mut self.k[T::STAGES]);
            s.stats.evaluations += 1;
        }
        Ok(s.tolerances
            .map_or(0.0, |tolerances| T::error(h, &self.k, y, y_new, tolerances)))
    }

    #[inline]
    fn accept(&mut self) {
        if T::ESTIMATE_READS_LAST {
            self.fsal = true;
        } else {
            // kₛ₊₁ is made by the next attempt, or by `dense` if the driver asks for it first.
            self.have_k1 = false;
        }
    }

    fn restart(&mut self, _: &M, _: f64, _: &M::State, _: &mut Stats) {
        self.fsal = false;
        self.have_k1 = false;
    }

    fn dense(
        &mut self,
        model: &M,
        mut s: Step<'_, M::State>,
        y_new: &M::State,
        dense: &mut DenseStep<M::State>,
    ) -> bool {
        if !self.fsal {
            model.derivative(s.t + s.h, y_new, &mut self.k[T::STAGES]);
            s.stats.evaluations += 1;
            self.fsal = true;
        }
        T::dense(
            model,
            s.reborrow(),
            y_new,
            &mut self.k,
            &mut self.probe,
            dense,
        );
        true
    }
}

/// out ← y + h·Σⱼ aⱼ·kⱼ, component by component so each sum stays in a register (a pass per
/// coefficient stored and reloaded the whole vector every time: 22 % of a DOP853 step on
/// Lorenz, measured with perf). Zero coefficients are skipped, which changes no bit of the sum.
#[inline(always)]
pub(super) fn combine<S: State>(out: &mut S, y: &S, h: f64, a: &[f64], k: &[S]) {
    let n = out.as_slice().len();
    let out = &mut out.as_mut_slice()[..n];
    let y = &y.as_slice()[..n];
    let k = &k[..a.len()];
    for i in 0..n {
        out[i] = y[i] + h * weighted(a, k, i);
    }
}

/// Σⱼ wⱼ·kⱼ[i] in order of j, skipping zero weights: the building block of stages and error
/// estimates.
#[inline(always)]
pub(super) fn weighted<S: State>(w: &[f64], k: &[S], i: usize) -> f64 {
    let mut sum = 0.0;
    for (wj, kj) in w.iter().zip(k) {
        if *wj != 0.0 {
            sum += wj * kj.as_slice()[i];
        }
    }
    sum
}
