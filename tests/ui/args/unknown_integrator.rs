use odyn::prelude::*;

#[system(integrator = Rk5)]
pub struct Spring {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
}

fn main() {}
