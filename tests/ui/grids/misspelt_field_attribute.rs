use odyn::grid::{Grid, Stencil};
use odyn::system;

#[system]
struct Heat {
    #[feild]
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
