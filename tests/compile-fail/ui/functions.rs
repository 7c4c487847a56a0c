//! Rejected models: functions. One module per case, named for what it gets wrong;
//! each must give its own error at the offending token and nothing more. (One file per
//! topic: trybuild compiles each file as a crate, and one crate per case cost a minute.)
#![allow(dead_code)]

mod extra_argument {
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
        fn acceleration(&self, k: usize) -> f64 {
            -(k as f64) * self.x
        }
    }

    fn main() {}
}

mod missing_acceleration {
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
        fn energy(&self) -> f64 {
            0.5 * (self.x * self.x + self.v * self.v)
        }
    }

    fn main() {}
}

mod missing_derivative {
    use odyn::prelude::*;

    #[system]
    pub struct Decay {
        #[state]
        pub n: f64,
        pub rate: f64,
    }

    #[system]
    impl Decay {
        fn half_life(&self) -> f64 {
            std::f64::consts::LN_2 / self.rate
        }
    }

    fn main() {}
}

mod mut_self {
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
        fn acceleration(&mut self) -> f64 {
            -self.x
        }
    }

    fn main() {}
}

mod no_return {
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
}

mod self_in_macro {
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
}

mod self_method_call {
    use odyn::prelude::*;

    #[system]
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
            -self.stiffness() * self.x
        }
    }

    impl Spring {
        fn stiffness(&self) -> f64 {
            self.k
        }
    }

    fn main() {}
}

mod self_passed_along {
    use odyn::prelude::*;

    #[system]
    pub struct Spring {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
    }

    fn force(spring: &Spring) -> f64 {
        -spring.x
    }

    #[system]
    impl Spring {
        fn acceleration(&self) -> f64 {
            force(self)
        }
    }

    fn main() {}
}

mod wrong_force_function {
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
        fn derivative(&self) -> SpringState {
            SpringState { x: self.v, v: -self.x }
        }
    }

    fn main() {}
}

fn main() {}
