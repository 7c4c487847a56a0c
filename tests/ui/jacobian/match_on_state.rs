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
        match self.x.partial_cmp(&0.0) {
            Some(o) => -(o as i32 as f64),
            None => 0.0,
        }
    }
}

fn main() {}
