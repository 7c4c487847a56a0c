use odyn::prelude::*;

const N: usize = 2;

#[system]
pub struct Decay {
    #[state]
    pub x: [f64; 2],
    pub k: f64,
}

#[system]
impl Decay {
    fn derivative(&self) -> DecayState {
        let mut rates = [0.0; N];
        rates[0] = -self.k * self.x[0];
        rates[1] = -self.k * self.x[1];
        DecayState { x: rates }
    }
}

fn main() {}
