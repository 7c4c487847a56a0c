use odyn::prelude::*;

#[system]
pub struct Decay {
    #[state]
    pub n: f64,
    pub rate: f64,
}

#[system]
impl Decay {
    fn half_life(&self) -> f64 {
        std::f64::consts::LN_2 / self.rate
    }
}

fn main() {}
