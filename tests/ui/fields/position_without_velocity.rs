use odyn::prelude::*;

#[system]
pub struct Pendulum {
    #[position]
    pub theta: f64,
    #[position]
    pub phi: f64,
    #[velocity]
    pub omega: f64,
}

fn main() {}
