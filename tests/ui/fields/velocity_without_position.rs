use odyn::prelude::*;

#[system]
pub struct Falling {
    #[velocity]
    pub v: f64,
    pub g: f64,
}

fn main() {}
