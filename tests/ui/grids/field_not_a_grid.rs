use odyn::grid::Stencil;
use odyn::system;

#[system]
struct Heat {
    #[field]
    u: Vec<f64>,
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
