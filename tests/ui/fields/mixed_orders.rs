use odyn::prelude::*;

#[system]
pub struct Confused {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
    #[state]
    pub charge: f64,
}

fn main() {}
