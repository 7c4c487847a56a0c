//! Rejected models: args. One module per case, named for what it gets wrong;
//! each must give its own error at the offending token and nothing more. (One file per
//! topic: trybuild compiles each file as a crate, and one crate per case cost a minute.)
#![allow(dead_code)]

mod args_on_impl {
    use odyn::prelude::*;

    #[system]
    pub struct Spring {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
    }

    #[system(dt = 0.1)]
    impl Spring {
        fn acceleration(&self) -> f64 {
            -self.x
        }
    }

    fn main() {}
}

mod duplicate_argument {
    use odyn::prelude::*;

    #[system(dt = 0.1, dt = 0.2)]
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
            -self.k * self.x
        }
    }

    fn main() {}
}

mod integer_division_dt {
    use odyn::prelude::*;

    #[system(dt = 1/60)]
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
            -self.k * self.x
        }
    }

    fn main() {}
}

mod non_positive_dt {
    use odyn::prelude::*;

    #[system(dt = 0.0)]
    pub struct Spring {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
    }

    fn main() {}
}

mod tolerance_on_fixed_step_method {
    use odyn::prelude::*;

    #[system(integrator = Rk4, rtol = 1e-6)]
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
            -self.k * self.x
        }
    }

    fn main() {}
}

mod unknown_argument {
    use odyn::prelude::*;

    #[system(integrator = Rk4, tolerance = 1e-6)]
    pub struct Spring {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
    }

    fn main() {}
}

mod unknown_integrator {
    use odyn::prelude::*;

    #[system(integrator = Rk5)]
    pub struct Spring {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
    }

    fn main() {}
}

fn main() {}

/// A wrong argument is its one error: the model still expands (with the default arguments), so
/// code that runs it and reads its state draws nothing more.
mod negative_rtol_model_still_used {
    use odyn::prelude::*;

    #[system(rtol = -1.0)]
    pub struct Ball {
        #[position]
        pub y: f64,
        #[velocity]
        pub v: f64,
        pub g: f64,
    }

    #[system]
    impl Ball {
        fn acceleration(&self) -> f64 {
            -self.g
        }
    }

    fn drop_height() -> odyn::Result<f64> {
        let ball = Ball { y: 1.0, v: 0.0, g: 9.81 };
        let run = ball.simulate().duration(0.1).run()?;
        Ok(run.last().state.y)
    }
}
