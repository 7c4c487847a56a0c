use odyn::particles::Spring;
use odyn::prelude::*;

#[system]
struct Net {
    #[position]
    x: Vec<Vector3<f64>>,
    #[velocity]
    v: Vec<Vector3<f64>>,
    #[mass]
    m: Vec<f64>,
    springs: Vec<Spring>,
}

#[system]
impl Net {
    #[pair(springs)]
    fn spring(&self, s: &Spring, xa: Vector3<f64>, xb: Vector3<f64>) -> Vector3<f64> {
        if (xb - xa).norm() > s.rest { (xb - xa) * s.stiffness } else { Vector3::zeros() }
    }
}

fn main() {}
