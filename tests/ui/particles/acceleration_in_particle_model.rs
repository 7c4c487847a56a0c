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
    #[particle]
    fn weight(&self, _x: Vector3<f64>) -> Vector3<f64> {
        Vector3::new(0.0, -9.81, 0.0)
    }

    fn acceleration(&self) -> Vector3<f64> {
        Vector3::zeros()
    }
}

fn main() {}
