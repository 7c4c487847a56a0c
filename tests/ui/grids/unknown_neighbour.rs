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
    #[cell]
    fn rate(&self, u: Stencil, v: Stencil) -> [f64; 2] {
        [u.nn - u.c, v.c * self.a]
    }
}

// The model still type-checks where it is used: no follow-on errors.
fn run(model: &Brusselator) {
    let _ = odyn::Model::simulate(model);
}

fn main() {
    let _ = run;
}
