use odyn::prelude::*;

#[system]
pub struct Particle {
    #[position]
    pub r: [f64; 2],
    #[velocity]
    pub v: [f64; 2],
    pub axis: usize,
}

#[system]
impl Particle {
    fn acceleration(&self) -> [f64; 2] {
        let along = self.r[self.axis];
        [-along, 0.0]
    }
}

fn main() {}
