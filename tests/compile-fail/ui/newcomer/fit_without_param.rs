use odyn::fit::{Data, FitOptions, fit};
use odyn::prelude::*;

// A model without `#[param]` fields passed to `fit`: the message says to mark them.
#[system]
#[derive(Clone, Copy)]
struct Decay {
    #[state]
    c: f64,
    k: f64,
}

#[system]
impl Decay {
    fn derivative(&self) -> DecayState {
        DecayState { c: -self.k * self.c }
    }
}

fn main() {
    let data: [Data; 0] = [];
    let _ = fit(&Decay { c: 1.0, k: 0.5 }, &data, &FitOptions::default());
}
