use odyn::grid::{Grid, Stencil};
use odyn::system;

#[system]
struct Heat {
    #[field]
    u: Grid,
    d: f64,
}

#[system]
impl Heat {
    #[cel]
    fn rate(&self, u: Stencil) -> f64 {
        self.d * u.laplacian()
    }
}

fn main() {}
