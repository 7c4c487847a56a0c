use odyn::prelude::*;

#[system]
pub struct Parameters {
    pub k: f64,
    pub m: f64,
}

fn main() {}
