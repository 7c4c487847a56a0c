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
    #[cell]
    fn rate(&self, u: Stencil) -> f64 {
        if u.c > 0.5 { self.d * u.laplacian() } else { 0.0 }
    }
}

fn main() {}
