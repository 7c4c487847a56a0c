use odyn::prelude::*;

#[system()]
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
        for i in 0..3 {
            if i == 2 {
                return 0.0;
            }
        }
        -self.k * self.x
    }
}

fn main() {}
