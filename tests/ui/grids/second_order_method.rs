use odyn::grid::{Grid, Stencil};
use odyn::system;

#[system(integrator = VelocityVerlet, dt = 0.1)]
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
