use odyn::prelude::*;

#[system(integrator = SymplecticEuler)]
pub struct Lorenz {
    #[state]
    pub x: f64,
    #[state]
    pub y: f64,
    #[state]
    pub z: f64,
}

fn main() {}
