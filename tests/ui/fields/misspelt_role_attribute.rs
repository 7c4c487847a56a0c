use odyn::prelude::*;

#[system]
pub struct Spring {
    #[postion]
    pub x: f64,
    #[velocity]
    pub v: f64,
    pub k: f64,
}

#[system]
impl Spring {
    fn acceleration(&self) -> f64 {
        -self.k * self.x
    }
}

fn main() {}
