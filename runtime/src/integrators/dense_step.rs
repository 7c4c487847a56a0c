//! The solution between the ends of one accepted step, as a polynomial in the fraction θ of the
//! step: what an integrator's continuous extension fills, and the drivers read for `save_at`,
//! events and dense output.

use crate::{Result, State};

/// y(t + θh) = Σₖ cₖ·θᵏ on one accepted step, θ ∈ [0, 1]: coefficient vectors c₀ … c_d.
///
/// Each method with its own continuous extension fills one from its stages (Tsit5's order-4
/// interpolant, DOP853's order-7 one, the Rosenbrock methods'); every other method gets the
/// cubic Hermite interpolant through y and f at both ends (`DenseStep::hermite`), order 3.
#[derive(Clone, Debug)]
pub struct DenseStep<S> {
    /// Start of the step.
    pub t: f64,
    /// Its size.
    pub h: f64,
    /// Coefficients c₀ … c_d; only the first `len` are in use.
    coefficients: Vec<S>,
    len: usize,
}

impl<S: State> DenseStep<S> {
    /// Room for polynomials of degree up to `degree`, every buffer shaped like `like`.
    ///
    /// Errors: [`Error::InvalidInput`] when a buffer cannot be allocated ([`State::try_clone`]).
    pub(crate) fn new(like: &S, degree: usize) -> Result<Self> {
        Ok(DenseStep {
            t: 0.0,
            h: 0.0,
            coefficients: (0..=degree)
                .map(|_| like.try_clone())
                .collect::<Result<_>>()?,
            len: 0,
        })
    }

    /// Starts filling a polynomial of `degree` for the step (t, h); returns its coefficient
    /// buffers, to be overwritten.
    pub(crate) fn fill(&mut self, t: f64, h: f64, degree: usize) -> &mut [S] {
        debug_assert!(degree < self.coefficients.len());
        self.t = t;
        self.h = h;
        self.len = degree + 1;
        &mut self.coefficients[..=degree]
    }

    /// The degree in use.
    pub fn degree(&self) -> usize {
        self.len.saturating_sub(1)
    }

    /// The coefficients in use, c₀ first.
    pub fn coefficients(&self) -> &[S] {
        &self.coefficients[..self.len]
    }

    /// Writes y(t + θh) into `out` by Horner's rule.
    pub fn eval(&self, theta: f64, out: &mut S) {
        let c = self.coefficients();
        let out = out.as_mut_slice();
        out.copy_from_slice(c[self.len - 1].as_slice());
        for ck in c[..self.len - 1].iter().rev() {
            for (o, a) in out.iter_mut().zip(ck.as_slice()) {
                *o = *o * theta + a;
            }
        }
    }

    /// The cubic Hermite interpolant through (y₀, f₀) at t and (y₁, f₁) at t + h:
    /// y(θ) = y₀ + θ·h·f₀ + θ²·(3Δ − h(2f₀ + f₁)) + θ³·(h(f₀ + f₁) − 2Δ), Δ = y₁ − y₀
    /// (Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.6, eq. (6.7)); order 3.
    pub(crate) fn hermite(&mut self, t: f64, h: f64, ends: [&S; 4]) {
        let [y0, f0, y1, f1] = ends.map(State::as_slice);
        let [c0, c1, c2, c3] = self.fill(t, h, 3) else {
            unreachable!("fill returns degree + 1 coefficients")
        };
        let parts = c0
            .as_mut_slice()
            .iter_mut()
            .zip(c1.as_mut_slice())
            .zip(c2.as_mut_slice())
            .zip(c3.as_mut_slice());
        for (i, (((a0, a1), a2), a3)) in parts.enumerate() {
            let delta = y1[i] - y0[i];
            *a0 = y0[i];
            *a1 = h * f0[i];
            *a2 = 3.0 * delta - h * (2.0 * f0[i] + f1[i]);
            *a3 = h * (f0[i] + f1[i]) - 2.0 * delta;
        }
    }
}
