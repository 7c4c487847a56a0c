//! Rejected models: differential–algebraic ones (`#[algebraic]` fields, `fn mass`). One module
//! per case, named for what it gets wrong; each must give its own error at the offending token
//! and nothing more.
#![allow(dead_code)]

mod algebraic_in_second_order {
    use odyn::prelude::*;

    #[system]
    pub struct Pendulum {
        #[position]
        pub q: [f64; 2],
        #[velocity]
        pub v: [f64; 2],
        #[algebraic]
        pub lambda: f64,
    }

    #[system]
    impl Pendulum {
        fn acceleration(&self) -> [f64; 2] {
            [-self.lambda * self.q[0], -self.lambda * self.q[1] - 9.81]
        }
    }

    fn main() {}
}

mod algebraic_in_const_generic {
    use odyn::prelude::*;

    #[system]
    pub struct Chain<const N: usize> {
        #[state]
        pub x: [f64; N],
        #[algebraic]
        pub z: [f64; N],
    }

    #[system]
    impl<const N: usize> Chain<N> {
        fn derivative(&self) -> ChainState<N> {
            ChainState { x: self.z, z: self.x }
        }
    }

    fn main() {}
}

mod algebraic_without_jacobian {
    use odyn::prelude::*;

    #[system(jacobian = false)]
    pub struct Equilibrium {
        #[state]
        pub x: f64,
        #[algebraic]
        pub z: f64,
    }

    #[system]
    impl Equilibrium {
        fn derivative(&self) -> EquilibriumState {
            EquilibriumState {
                x: -self.x,
                z: self.z - self.x,
            }
        }
    }

    fn main() {}
}

mod fully_implicit_residual {
    use odyn::prelude::*;

    #[system]
    pub struct Implicit {
        #[state]
        pub x: f64,
    }

    #[system]
    impl Implicit {
        fn derivative(&self) -> ImplicitState {
            ImplicitState { x: -self.x }
        }
        fn residual(&self, rate: f64) -> f64 {
            rate + self.x
        }
    }

    fn main() {}
}

mod mass_of_time {
    use odyn::prelude::*;

    #[system]
    pub struct Circuit {
        #[state]
        pub u: [f64; 2],
    }

    #[system]
    impl Circuit {
        fn derivative(&self) -> CircuitState {
            CircuitState { u: [-self.u[0], -self.u[1]] }
        }
        fn mass(&self, t: f64) -> [[f64; 2]; 2] {
            [[1.0, 0.0], [0.0, t]]
        }
    }

    fn main() {}
}

mod mass_reads_state {
    use odyn::prelude::*;

    #[system]
    pub struct Circuit {
        #[state]
        pub u: [f64; 2],
    }

    #[system]
    impl Circuit {
        fn derivative(&self) -> CircuitState {
            CircuitState { u: [-self.u[0], -self.u[1]] }
        }
        fn mass(&self) -> [[f64; 2]; 2] {
            [[1.0, 0.0], [0.0, self.u[0]]]
        }
    }

    fn main() {}
}

mod mass_without_return {
    use odyn::prelude::*;

    #[system]
    pub struct Circuit {
        #[state]
        pub u: [f64; 2],
    }

    #[system]
    impl Circuit {
        fn derivative(&self) -> CircuitState {
            CircuitState { u: [-self.u[0], -self.u[1]] }
        }
        fn mass(&self) {}
    }

    fn main() {}
}

fn main() {}
