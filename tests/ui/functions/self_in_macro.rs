use odyn::prelude::*;

#[system]
pub struct Spring {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
}

#[system]
impl Spring {
    fn acceleration(&self) -> f64 {
        debug_assert!(self.x.is_finite());
        -self.x
    }
}

fn main() {}
