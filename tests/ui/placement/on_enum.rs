use odyn::prelude::*;

#[system]
pub enum Phase {
    Solid,
    Liquid,
}

fn main() {}
