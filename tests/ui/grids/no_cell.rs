use odyn::grid::{Grid, Stencil};
use odyn::system;

#[system]
struct Brusselator {
    #[field]
    u: Grid,
    #[field]
    v: Grid,
    a: f64,
}

#[system]
impl Brusselator {
    fn rate(&self, u: Stencil, v: Stencil) -> [f64; 2] {
        [u.c, v.c * self.a]
    }
}

fn main() {}
