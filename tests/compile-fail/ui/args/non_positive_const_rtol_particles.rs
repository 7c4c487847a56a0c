//! The `const` check of `rtol` holds for a particle model as for a fixed-size one: the model is
//! never run, yet its bad `rtol` is an error.
use odyn::prelude::*;

const TOLERANCE: f64 = -1e-6;

#[system(integrator = Tsit5, rtol = TOLERANCE)]
struct Drops {
    #[position]
    x: Vec<Vector3<f64>>,
    #[velocity]
    v: Vec<Vector3<f64>>,
    #[mass]
    m: Vec<f64>,
}

#[system]
impl Drops {
    #[particle]
    fn weight(&self, _x: Vector3<f64>) -> Vector3<f64> {
        Vector3::new(0.0, -9.81, 0.0)
    }
}

fn main() {}
