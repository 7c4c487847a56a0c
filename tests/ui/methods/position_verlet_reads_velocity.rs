use odyn::prelude::*;

#[system(integrator = PositionVerlet, dt = 0.01)]
pub struct Spring {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
    pub k: f64,
    pub b: f64,
}

#[system]
impl Spring {
    fn acceleration(&self) -> f64 {
        -self.k * self.x - self.b * self.v
    }
}

fn main() {}
