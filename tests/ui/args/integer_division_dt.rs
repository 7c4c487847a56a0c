use odyn::prelude::*;

#[system(dt = 1/60)]
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
