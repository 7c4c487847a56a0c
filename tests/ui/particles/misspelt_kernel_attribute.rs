use odyn::particles::Spring;
use odyn::prelude::*;

#[system]
struct Beads {
    #[position]
    x: Vec<Vector3<f64>>,
    #[velocity]
    v: Vec<Vector3<f64>>,
    #[mass]
    m: Vec<f64>,
    springs: Vec<Spring>,
}

#[system]
impl Beads {
    #[piar(springs)]
    fn spring(&self, s: &Spring, xa: Vector3<f64>, xb: Vector3<f64>) -> Vector3<f64> {
        let d = xb - xa;
        d / d.norm() * (s.stiffness * (d.norm() - s.rest))
    }
}

fn main() {}
