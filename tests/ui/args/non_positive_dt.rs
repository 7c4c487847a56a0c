use odyn::prelude::*;

#[system(dt = 0.0)]
pub struct Spring {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
}

fn main() {}
