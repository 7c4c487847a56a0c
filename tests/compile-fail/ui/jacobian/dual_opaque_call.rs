use odyn::system;

/// A function of `f64` only: a dual number cannot be passed to it.
fn restoring(x: f64) -> f64 {
    -x * (1.0 + x * x)
}

// `jacobian = dual` evaluates the code as written over dual numbers: the error is at the call
// that takes an `f64`, where a function generic over the number type would take the dual.
#[system(jacobian = dual)]
struct Spring {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
}

#[system]
impl Spring {
    fn acceleration(&self) -> f64 {
        restoring(self.x) - 0.1 * self.v
    }
}

fn main() {}
