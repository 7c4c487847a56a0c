use odyn::prelude::*;

#[system]
pub struct Particle {
    #[position]
    pub r: Vector2<f64>,
    #[velocity]
    pub v: Vector2<f64>,
}

#[system]
impl Particle {
    fn acceleration(&self) -> Vector2<f64> {
        -self.r * self.r
    }
}

fn main() {}
