//! Yoshida's sixth-order composition of leapfrog ("solution A").
#![allow(
    clippy::excessive_precision,
    reason = "the weights are quoted with the 20 digits their source prints"
)]

use super::composition::{Composition, Weights};
use crate::Method;

/// Yoshida's sixth-order method: seven leapfrog substeps with the symmetric weights
///
/// γ₁ = γ₇ = 0.78451361047755726382, γ₂ = γ₆ = 0.23557321335935813368,
/// γ₃ = γ₅ = −1.17767998417887100695, γ₄ = 1 − 2(γ₁ + γ₂ + γ₃) = 1.31518632068391121888.
///
/// See [`Composition`] for the step.
///
/// - **Order** 6; 7 force evaluations a step.
/// - **Energy**: symplectic, bounded.
/// - **Stability** on ẍ = −ω²x: ωh < 2.2691 (from the composed one-step matrix; measured in
///   `tests/integration/compositions.rs`).
///
/// Reference: H. Yoshida, "Construction of higher order symplectic integrators", Phys. Lett. A
/// 150 (1990) 262–268, Table 1, solution A (there to 15 digits); the 20-digit values as printed in
/// Hairer, Lubich & Wanner, *Geometric Numerical Integration*, 2nd ed., 2006, §V.3, eq. (3.11).
pub type Yoshida6<S> = Composition<S, Yoshida6Weights>;

/// The weights the stability explorer reads.
pub(crate) type Substeps = Yoshida6Weights;

/// The weights of [`Yoshida6`].
#[derive(Clone, Copy, Debug)]
pub struct Yoshida6Weights;

const G1: f64 = 0.784_513_610_477_557_263_82;
const G2: f64 = 0.235_573_213_359_358_133_68;
const G3: f64 = -1.177_679_984_178_871_006_95;

impl crate::integrators::sealed::Sealed for Yoshida6Weights {}

impl Weights for Yoshida6Weights {
    const METHOD: Method = Method::Yoshida6;
    const WEIGHTS: &'static [f64] = &[G1, G2, G3, 1.0 - 2.0 * (G1 + G2 + G3), G3, G2, G1];
}
