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
        self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x * (1.0 + self.x))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))
    }
}

fn main() {}
