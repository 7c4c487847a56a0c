use odyn::prelude::*;

#[system]
pub struct Spring<T> {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
    pub k: T,
}

fn main() {}
