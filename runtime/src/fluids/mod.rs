//! Fluids beside the ODE models: Stam's Stable Fluids on a grid.
//!
//! A `#[system]` model is an ODE y′ = f(t, y) with a topology fixed at compile time (fixed-size
//! models) or at the start of a run (particle models), so odyn can differentiate f and factorize
//! its Jacobian once per run. A grid fluid is not stepped that way: each step is a sequence of
//! operators — advection along the flow, implicit diffusion, pressure projection — each exact for
//! its own sub-problem (operator splitting, Stam 1999). The grid itself is still static, so what
//! carries over is the linear algebra: the projection's Poisson matrix and the diffusion matrix
//! depend only on the grid (and the step), and are factorized by faer's sparse Cholesky once,
//! after which every step only substitutes.
//!
//! [`StableFluids`] is that solver on a staggered (MAC) grid.

mod stable_fluids;

pub use stable_fluids::{FluidOptions, StableFluids};
