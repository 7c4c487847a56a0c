use odyn::prelude::*;

#[system]
pub struct Spring {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
}

fn force(spring: &Spring) -> f64 {
    -spring.x
}

#[system]
impl Spring {
    fn acceleration(&self) -> f64 {
        force(self)
    }
}

fn main() {}
