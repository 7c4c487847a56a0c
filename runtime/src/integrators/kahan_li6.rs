//! Kahan and Li's optimised sixth-order composition of leapfrog.
#![allow(
    clippy::excessive_precision,
    reason = "the weights are quoted with the 20 digits their source prints"
)]

use super::composition::{Composition, Weights};
use crate::Method;

/// Kahan and Li's sixth-order method: nine leapfrog substeps with the symmetric weights
///
/// γ₁ = γ₉ = 0.39216144400731413928, γ₂ = γ₈ = 0.33259913678935943860,
/// γ₃ = γ₇ = −0.70624617255763935981, γ₄ = γ₆ = 0.08221359629355080023,
/// γ₅ = 0.79854399093482996340.
///
/// Two more substeps than [`Yoshida6`](super::Yoshida6) buy weights of smaller magnitude
/// (max |γᵢ| 0.80 against 1.32), chosen to minimise the leading error term: at equal cost its
/// error is far smaller, the optimised sixth-order choice of HLW's comparison (§V.3.2, Fig. 3.4).
/// See [`Composition`] for the step.
///
/// - **Order** 6; 9 force evaluations a step.
/// - **Energy**: symplectic, bounded.
/// - **Stability** on ẍ = −ω²x: ωh < 2.5326 (from the composed one-step matrix; measured in
///   `tests/integration/compositions.rs`).
///
/// Reference: W. Kahan and R.-C. Li, "Composition constants for raising the orders of
/// unconventional schemes for ordinary differential equations", Math. Comp. 66 (1997)
/// 1089–1099; the weights as printed in Hairer, Lubich & Wanner, *Geometric Numerical
/// Integration*, 2nd ed., 2006, §V.3, eq. (3.12).
pub type KahanLi6<S> = Composition<S, KahanLi6Weights>;

/// The weights the stability explorer reads.
pub(crate) type Substeps = KahanLi6Weights;

/// The weights of [`KahanLi6`].
#[derive(Clone, Copy, Debug)]
pub struct KahanLi6Weights;

const G1: f64 = 0.392_161_444_007_314_139_28;
const G2: f64 = 0.332_599_136_789_359_438_60;
const G3: f64 = -0.706_246_172_557_639_359_81;
const G4: f64 = 0.082_213_596_293_550_800_23;
const G5: f64 = 0.798_543_990_934_829_963_40;

impl crate::integrators::sealed::Sealed for KahanLi6Weights {}

impl Weights for KahanLi6Weights {
    const METHOD: Method = Method::KahanLi6;
    const WEIGHTS: &'static [f64] = &[G1, G2, G3, G4, G5, G4, G3, G2, G1];
}
