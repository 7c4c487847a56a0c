use odyn::prelude::*;

#[system]
pub struct Spring(f64, f64);

fn main() {}
