use odyn::prelude::*;

// The impl block lacks `#[system]`: the struct's expansion says so at the struct's name.
#[system]
struct Spring {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
}

impl Spring {
    fn acceleration(&self) -> f64 {
        -self.x
    }
}

fn main() {}
