use odyn::prelude::*;

#[system(integrator = PositionVerlet)]
struct Net {
    #[position]
    x: Vec<Vector3<f64>>,
    #[velocity]
    v: Vec<Vector3<f64>>,
    #[mass]
    m: Vec<f64>,
}

#[system]
impl Net {
    #[particle]
    fn drag(&self, _x: Vector3<f64>, v: Vector3<f64>) -> Vector3<f64> {
        -v
    }
}

fn main() {}
