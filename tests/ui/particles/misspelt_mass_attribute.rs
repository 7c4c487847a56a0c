use odyn::prelude::*;

#[system]
struct Beads {
    #[position]
    x: Vec<Vector3<f64>>,
    #[velocity]
    v: Vec<Vector3<f64>>,
    #[mas]
    m: Vec<f64>,
}

#[system]
impl Beads {
    #[particle]
    fn gravity(&self, x: Vector3<f64>) -> Vector3<f64> {
        Vector3::new(0.0, 0.0, -9.81) + 0.0 * x
    }
}

fn main() {}
