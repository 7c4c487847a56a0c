use odyn::prelude::*;

#[system]
struct Beads {
    #[position]
    x: Vec<f64>,
    #[velocity]
    v: Vec<Vector3<f64>>,
    #[mass]
    m: Vec<f64>,
}

fn main() {}
