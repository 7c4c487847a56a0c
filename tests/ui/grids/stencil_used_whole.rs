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

fn spread(s: Stencil) -> f64 {
    s.e - s.w
}

#[system]
impl Brusselator {
    #[cell]
    fn rate(&self, u: Stencil, v: Stencil) -> [f64; 2] {
        [spread(u), v.c * self.a]
    }
}

fn main() {}
