use odyn::prelude::*;

#[system]
pub struct Spring {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
}

#[system]
impl Spring {
    fn energy(&self) -> f64 {
        0.5 * (self.x * self.x + self.v * self.v)
    }
}

fn main() {}
