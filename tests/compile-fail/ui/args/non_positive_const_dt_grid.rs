//! The `const` check of `dt` holds for a field model as for a fixed-size one: the model is never
//! run, yet its bad `dt` is an error.
use odyn::grid::{Grid, Stencil};
use odyn::system;

const STEP: f64 = -0.01;

#[system(dt = STEP)]
struct Heat {
    #[field]
    u: Grid,
    d: f64,
}

#[system]
impl Heat {
    #[cell]
    fn rate(&self, u: Stencil) -> f64 {
        self.d * u.laplacian()
    }
}

fn main() {}
