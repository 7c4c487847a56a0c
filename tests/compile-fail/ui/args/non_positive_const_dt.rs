use odyn::prelude::*;

const STEP: f64 = -0.01;

#[system(dt = STEP)]
pub struct Model {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
    pub k: f64,
}

#[system]
impl Model {
    fn acceleration(&self) -> f64 {
        -self.k * self.x
    }
}

fn main() {}
