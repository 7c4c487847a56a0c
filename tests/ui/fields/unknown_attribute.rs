use odyn::prelude::*;

// No derive on the struct could own `#[units]`, so it is an error, and the only one.
#[system]
pub struct Decay {
    #[state]
    pub x: f64,
    #[units(per_second)]
    pub k: f64,
}

#[system]
impl Decay {
    fn derivative(&self) -> DecayState {
        DecayState { x: -self.k * self.x }
    }
}

fn main() {}
