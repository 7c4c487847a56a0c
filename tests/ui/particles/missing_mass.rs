use odyn::particles::Spring;
use odyn::prelude::*;

#[system]
struct Beads {
    #[position]
    x: Vec<Vector3<f64>>,
    #[velocity]
    v: Vec<Vector3<f64>>,
    springs: Vec<Spring>,
}

fn main() {}
