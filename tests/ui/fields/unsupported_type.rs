use odyn::prelude::*;

#[system]
pub struct Spring {
    #[position]
    pub x: f32,
    #[velocity]
    pub v: f32,
}

fn main() {}
