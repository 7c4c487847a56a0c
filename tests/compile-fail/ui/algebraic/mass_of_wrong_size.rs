//! A `fn mass` whose matrix is not as large as the state: a type error at its return type.
use odyn::prelude::*;

#[system]
pub struct Circuit {
    #[state]
    pub u: [f64; 2],
    #[algebraic]
    pub z: f64,
}

#[system]
impl Circuit {
    fn derivative(&self) -> CircuitState {
        CircuitState {
            u: [-self.u[0], -self.u[1]],
            z: self.z - self.u[0],
        }
    }
    fn mass(&self) -> [[f64; 2]; 2] {
        [[1.0, 0.0], [0.0, 1.0]]
    }
}

fn main() {}
