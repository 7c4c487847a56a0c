//! Rejected models: helper functions (`#[odyn::function]`). One module per case, named for what
//! it gets wrong; each must give its own error at the offending token and nothing more.
#![allow(dead_code)]

mod recursive {
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
            -Self::halve(self.x)
        }

        #[odyn::function]
        fn halve(x: f64) -> f64 {
            if x > 1.0 { Self::halve(x / 2.0) } else { x }
        }
    }
}

mod mutually_recursive {
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
            self.even(self.x)
        }

        #[odyn::function]
        fn even(&self, x: f64) -> f64 {
            if x > 1.0 { self.odd(x - 1.0) } else { -self.k * x }
        }

        #[odyn::function]
        fn odd(&self, x: f64) -> f64 {
            -self.even(x - 1.0)
        }
    }
}

mod unsupported_in_helper {
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
            -Self::stepped(self.x)
        }

        #[odyn::function]
        fn stepped(x: f64) -> f64 {
            x.floor()
        }
    }
}

mod argument_not_a_number {
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
            self.stiffness(3) * self.x
        }

        #[odyn::function]
        fn stiffness(&self, n: usize) -> f64 {
            -self.k * n as f64
        }
    }
}

mod returns_not_a_number {
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
            if Self::outside(self.x) { -self.x } else { 0.0 }
        }

        #[odyn::function]
        fn outside(x: f64) -> bool {
            x > 1.0
        }
    }
}

mod helper_reads_the_state {
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
            self.restoring()
        }

        #[odyn::function]
        fn restoring(&self) -> f64 {
            -self.k * self.x
        }
    }
}

mod free_function_marked {
    #[odyn::function]
    fn cubic(x: f64) -> f64 {
        -x * x * x
    }
}

fn main() {}
