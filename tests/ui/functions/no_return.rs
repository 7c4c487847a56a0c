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
    fn acceleration(&self) {
        let _ = self.x;
    }
}

fn main() {}
