use odyn::prelude::*;

#[system]
pub struct Spring {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
    pub k: f64,
}

#[system]
impl Spring {
    fn acceleration(&self) -> f64 {
        -self.stiffness() * self.x
    }
}

impl Spring {
    fn stiffness(&self) -> f64 {
        self.k
    }
}

fn main() {}
