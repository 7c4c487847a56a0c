use odyn::prelude::*;

#[system]
pub struct Spring {
    #[position]
    #[velocity]
    pub x: f64,
    #[velocity]
    pub v: f64,
}

fn main() {}
