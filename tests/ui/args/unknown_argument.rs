use odyn::prelude::*;

#[system(integrator = Rk4, tolerance = 1e-6)]
pub struct Spring {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
}

fn main() {}
