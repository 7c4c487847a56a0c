//! Rejected models: methods. One module per case, named for what it gets wrong;
//! each must give its own error at the offending token and nothing more. (One file per
//! topic: trybuild compiles each file as a crate, and one crate per case cost a minute.)
#![allow(dead_code)]

mod position_verlet_reads_velocity {
    use odyn::prelude::*;

    #[system(integrator = PositionVerlet, dt = 0.01)]
    pub struct Spring {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
        pub k: f64,
        pub b: f64,
    }

    #[system]
    impl Spring {
        fn acceleration(&self) -> f64 {
            -self.k * self.x - self.b * self.v
        }
    }

    fn main() {}
}

mod symplectic_on_first_order {
    use odyn::prelude::*;

    #[system(integrator = SymplecticEuler)]
    pub struct Lorenz {
        #[state]
        pub x: f64,
        #[state]
        pub y: f64,
        #[state]
        pub z: f64,
    }

    fn main() {}
}

fn main() {}
