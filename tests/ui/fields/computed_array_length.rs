use odyn::prelude::*;

const N: usize = 4;

#[system]
pub struct Grid {
    #[state]
    pub u: [f64; N * N],
}

fn main() {}
