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
    springs: [Spring; 4],
}

#[system]
impl Net {
    #[pair(springs)]
    fn spring(&self, s: &Spring, xa: Vector3<f64>, xb: Vector3<f64>) -> Vector3<f64> {
        (xb - xa) * s.stiffness
    }

    #[pair(ropes)]
    fn rope(&self, s: &Spring, xa: Vector3<f64>, xb: Vector3<f64>) -> Vector3<f64> {
        (xb - xa) * s.stiffness
    }
}

fn main() {}
