//! Rejected models: control flow the Jacobian cannot follow (branches, loops and returns on the
//! state). One module per case, named for what it gets wrong;
//! each must give its own error at the offending token and nothing more. (One file per
//! topic: trybuild compiles each file as a crate, and one crate per case cost a minute.)
#![allow(dead_code)]

mod call_as_condition_on_state {
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
            if self.x > 0.0 && self.v.is_sign_positive() { -self.k } else { self.k }
        }
    }

    fn main() {}
}

mod guard_on_state {
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
            match self.k as u32 {
                0 if self.x.is_sign_positive() => -self.x,
                _ => self.x,
            }
        }
    }

    fn main() {}
}

mod let_pattern {
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
            let &a = &self.x;
            -a
        }
    }

    fn main() {}
}

mod loop_body_reads_state {
    use odyn::prelude::*;

    #[system()]
    pub struct Model {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
        pub n: usize,
    }

    #[system]
    impl Model {
        fn acceleration(&self) -> f64 {
            let mut a = 0.0;
            for _ in 0..self.n {
                a -= self.x;
            }
            a
        }
    }

    fn main() {}
}

mod break_in_loop_on_state {
    use odyn::prelude::*;

    #[system()]
    pub struct Model {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
        pub stop: bool,
    }

    #[system]
    impl Model {
        fn acceleration(&self) -> f64 {
            let mut a = 0.0;
            for _ in 0..3 {
                if self.stop {
                    break;
                }
                a -= self.x;
            }
            a
        }
    }

    fn main() {}
}

mod unrolled_too_far {
    use odyn::prelude::*;

    #[system()]
    pub struct Model {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
    }

    #[system]
    impl Model {
        fn acceleration(&self) -> f64 {
            let mut a = 0.0;
            for _ in 0..100_000 {
                a -= self.x;
            }
            a
        }
    }

    fn main() {}
}

mod match_on_state {
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
            match self.x.partial_cmp(&0.0) {
                Some(o) => -(o as i32 as f64),
                None => 0.0,
            }
        }
    }

    fn main() {}
}

mod match_binding_shadows_a_local {
    use odyn::prelude::*;

    #[system()]
    pub struct Model {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
    }

    #[system]
    impl Model {
        fn acceleration(&self) -> f64 {
            let d = 2.0;
            match self.x {
                d if d < 0.0 => -d,
                _ => d * self.x,
            }
        }
    }

    fn main() {}
}

mod nested_loops_to_a_changing_local {
    use odyn::prelude::*;

    #[system()]
    pub struct Model {
        #[state]
        pub x: [[f64; 2]; 2],
        pub n: usize,
    }

    #[system]
    impl Model {
        fn derivative(&self) -> ModelState {
            let mut d = [[0.0; 2]; 2];
            let mut m = self.n;
            for i in 0..m {
                m -= 1;
                for j in 0..m {
                    d[i][j] = -self.x[i][j];
                }
            }
            ModelState { x: d }
        }
    }

    fn main() {}
}

mod return_in_loop {
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
            for i in 0..3 {
                if i == 2 {
                    return 0.0;
                }
            }
            -self.k * self.x
        }
    }

    fn main() {}
}

mod state_in_loop_bound {
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
            let mut a = 0.0;
            for _ in 0..(self.x as usize) {
                a -= 1.0;
            }
            a
        }
    }

    fn main() {}
}

mod while_body_reads_state {
    use odyn::prelude::*;

    #[system()]
    pub struct Model {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
        pub n: usize,
    }

    #[system]
    impl Model {
        fn acceleration(&self) -> f64 {
            let mut a = 0.0;
            let mut i = 0;
            while i < self.n {
                a = a - self.x;
                i += 1;
            }
            a
        }
    }

    fn main() {}
}

mod state_arm_changes_outer_local {
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
            let mut k = self.k;
            if self.x < 0.0 {
                k = 10.0 * self.k;
            }
            -k * self.x
        }
    }

    fn main() {}
}

mod code_after_state_return_changes_outer_local {
    use odyn::prelude::*;

    #[system()]
    pub struct Model {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
        pub g: f64,
    }

    #[system]
    impl Model {
        fn acceleration(&self) -> f64 {
            let mut g = self.g;
            if self.x > 3.0 {
                return 0.0;
            }
            g *= 2.0;
            -g * self.x
        }
    }

    fn main() {}
}

mod loop_over_an_iterator {
    use odyn::system;

    // A `for` over something other than a range the macro can unroll.
    #[system]
    struct Chain {
        #[state]
        x: [f64; 3],
    }

    #[system]
    impl Chain {
        fn derivative(&self) -> ChainState {
            let mut out = [0.0; 3];
            for k in (0..3).rev() {
                out[k] = -self.x[k];
            }
            ChainState { x: out }
        }
    }

    fn main() {}
}

fn main() {}
