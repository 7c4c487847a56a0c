use odyn::prelude::*;

#[system()]
pub struct Model {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
    pub k: f64,
}

fn stiffness(x: f64) -> f64 {
    1.0 + x * x
}

#[system]
impl Model {
    fn acceleration(&self) -> f64 {
        -stiffness(self.x) * self.x
    }
}

fn main() {}
