//! Yoshida's fourth-order composition of leapfrog.

use super::composition::{Composition, Weights};
use crate::Method;

/// Yoshida's fourth-order method: leapfrog substeps of γ₁h, γ₂h, γ₁h with
///
/// γ₁ = 1/(2 − 2^⅓) = 1.3512071919596578, γ₂ = −2^⅓/(2 − 2^⅓) = −1.7024143839193153.
///
/// The middle substep runs backwards. See [`Composition`] for the step.
///
/// - **Order** 4; 3 force evaluations a step.
/// - **Energy**: symplectic, bounded.
/// - **Stability** on ẍ = −ω²x: ωh < 1.5734 (from the composed one-step matrix; measured in
///   `tests/integration/compositions.rs`).
///
/// Reference: H. Yoshida, "Construction of higher order symplectic integrators", Phys. Lett. A
/// 150 (1990) 262–268, eq. (4.4); also M. Suzuki, Phys. Lett. A 146 (1990) 319, and Hairer,
/// Lubich & Wanner, *Geometric Numerical Integration*, 2nd ed., 2006, §II.4, eq. (4.4).
pub type Yoshida4<S> = Composition<S, Yoshida4Weights>;

/// The weights the stability explorer reads.
pub(crate) type Substeps = Yoshida4Weights;

/// The weights of [`Yoshida4`].
#[derive(Clone, Copy, Debug)]
pub struct Yoshida4Weights;

/// 2^⅓ (f64 has no const cube root; 1.2599210498948731647672106 to 25 digits).
const CBRT_2: f64 = 1.259_921_049_894_873_2;

impl crate::integrators::sealed::Sealed for Yoshida4Weights {}

impl Weights for Yoshida4Weights {
    const METHOD: Method = Method::Yoshida4;
    const WEIGHTS: &'static [f64] = &[
        1.0 / (2.0 - CBRT_2),
        -CBRT_2 / (2.0 - CBRT_2),
        1.0 / (2.0 - CBRT_2),
    ];
}
