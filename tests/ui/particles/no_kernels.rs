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
    fn potential(&self) -> f64 {
        0.0
    }
}

fn main() {}
