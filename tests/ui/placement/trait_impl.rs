use odyn::prelude::*;

#[system]
pub struct Spring {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
}

#[system]
impl Default for Spring {
    fn default() -> Self {
        Spring { x: 1.0, v: 0.0 }
    }
}

fn main() {}
