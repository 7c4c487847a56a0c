use odyn::prelude::*;

#[system]
pub struct Particle {
    #[position]
    pub r: Vector3<f64>,
    #[velocity]
    pub v: Vector2<f64>,
}

fn main() {}
