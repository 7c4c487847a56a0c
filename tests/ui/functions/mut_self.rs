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
    fn acceleration(&mut self) -> f64 {
        -self.x
    }
}

fn main() {}
