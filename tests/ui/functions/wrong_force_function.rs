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
    fn derivative(&self) -> SpringState {
        SpringState { x: self.v, v: -self.x }
    }
}

fn main() {}
