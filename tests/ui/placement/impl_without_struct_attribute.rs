use odyn::prelude::*;

pub struct Spring {
    pub x: f64,
    pub v: f64,
}

#[system]
impl Spring {
    fn acceleration(&self) -> f64 {
        -self.x
    }
}

fn main() {}
