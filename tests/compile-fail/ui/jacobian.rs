//! Rejected models: jacobian. One module per case, named for what it gets wrong;
//! each must give its own error at the offending token and nothing more. (One file per
//! topic: trybuild compiles each file as a crate, and one crate per case cost a minute.)
#![allow(dead_code)]

mod cast_of_state {
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
            -((self.x as f32) as f64)
        }
    }

    fn main() {}
}

mod component_of_an_opaque_local {
    use odyn::prelude::*;

    const N: usize = 2;

    #[system]
    pub struct Decay {
        #[state]
        pub x: [f64; 2],
        pub k: f64,
    }

    #[system]
    impl Decay {
        fn derivative(&self) -> DecayState {
            let mut rates = [0.0; N];
            rates[0] = -self.k * self.x[0];
            rates[1] = -self.k * self.x[1];
            DecayState { x: rates }
        }
    }

    fn main() {}
}

mod implicit_without_jacobian {
    use odyn::prelude::*;

    #[system(integrator = ImplicitEuler, jacobian = false)]
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
            -self.x
        }
    }

    fn main() {}
}

mod non_integer_powi {
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
            -self.x.powi(self.k as i32)
        }
    }

    fn main() {}
}

mod non_literal_index {
    use odyn::prelude::*;

    #[system]
    pub struct Particle {
        #[position]
        pub r: [f64; 2],
        #[velocity]
        pub v: [f64; 2],
        pub axis: usize,
    }

    #[system]
    impl Particle {
        fn acceleration(&self) -> [f64; 2] {
            let along = self.r[self.axis];
            [-along, 0.0]
        }
    }

    fn main() {}
}

mod rejected_impl_has_no_follow_on_errors {
    use odyn::prelude::*;

    #[system(dt = 0.01)]
    pub struct Spring {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
        pub k: f64,
    }

    #[system]
    impl Spring {
        fn acceleration(&self) -> f64 {
            self.x.floor()
        }
    }

    fn main() {
        let model = Spring { x: 1.0, v: 0.0, k: 1.0 };
        let run = model.simulate().steps(10).run().unwrap();
        let _ = run.last().state.x;
    }
}

mod state_exponent {
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
            -self.x.powf(self.v)
        }
    }

    fn main() {}
}

// A function odyn cannot see inside is differentiated by differences of the call when it takes
// numbers; a vector argument is refused.
mod unsupported_call {
    use odyn::prelude::*;

    #[system()]
    pub struct Model {
        #[position]
        pub x: Vector2<f64>,
        #[velocity]
        pub v: Vector2<f64>,
        pub k: f64,
    }

    fn stiffness(x: Vector2<f64>) -> f64 {
        1.0 + x.norm_squared()
    }

    #[system]
    impl Model {
        fn acceleration(&self) -> Vector2<f64> {
            -self.x * stiffness(self.x)
        }
    }

    fn main() {}
}

// A method of a number odyn does not know is differentiated by differences of the call; one of
// a vector is refused.
mod unsupported_method {
    use odyn::prelude::*;

    #[system()]
    pub struct Model {
        #[position]
        pub x: Vector2<f64>,
        #[velocity]
        pub v: Vector2<f64>,
        pub k: f64,
    }

    #[system]
    impl Model {
        fn acceleration(&self) -> Vector2<f64> {
            -self.x * self.x.amax()
        }
    }

    fn main() {}
}

mod unsupported_operator {
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
            -(self.x % self.k)
        }
    }

    fn main() {}
}

mod unknown_jacobian_kind {
    use odyn::system;

    #[system(jacobian = numeric)]
    struct Decay {
        #[state]
        c: f64,
    }

    #[system]
    impl Decay {
        fn derivative(&self) -> DecayState {
            DecayState { c: -self.c }
        }
    }

    fn main() {}
}

fn main() {}
