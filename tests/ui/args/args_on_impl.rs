use odyn::prelude::*;

#[system]
pub struct Spring {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
}

#[system(dt = 0.1)]
impl Spring {
    fn acceleration(&self) -> f64 {
        -self.x
    }
}

fn main() {}
