use odyn::prelude::*;

#[system()]
pub struct Model {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
    pub k: f64,
}

#[system]
impl Model {
    fn acceleration(&self) -> f64 {
        match self.k as u32 {
            0 if self.x > 0.0 => -self.x,
            _ => self.x,
        }
    }
}

fn main() {}
