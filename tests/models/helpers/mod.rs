//! Helper functions marked `#[odyn::function]`: the Jacobians the macro derives by inlining them
//! against central differences, ∂f/∂t through a helper, and runs of a model with helpers against
//! the same model with the helpers inlined by hand.
//!
//! Tolerance: `common::check` compares with central differences at h = 1e-6·(1 + |yⱼ|): the
//! truncation error is O(h²·|f‴|) ≈ 1e-12 and the rounding error O(ε·|f|/h) ≈ 1e-10 relative to
//! the row's scale for these smooth, O(1)–O(100) forces, so 1e-6 relative fails on any wrong
//! derivative (a missing term is O(1)) and never on a right one. The random states stay off the
//! measure-zero kinks of `abs` and of the `if`s, where a difference quotient straddles two arms.

mod forms;
mod kernels;
mod nested;
mod opaque;
