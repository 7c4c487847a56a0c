//! Rejected models: `#[param]` fields (∂f/∂p). One module per case, named for what it gets
//! wrong; each must give its own error at the offending token and nothing more.
#![allow(dead_code)]

mod param_is_an_array {
    use odyn::system;

    #[system]
    struct Decay {
        #[state]
        c: f64,
        #[param]
        rates: [f64; 2],
    }

    #[system]
    impl Decay {
        fn derivative(&self) -> DecayState {
            DecayState { c: -self.rates[0] * self.c }
        }
    }
}

mod param_is_state {
    use odyn::system;

    #[system]
    struct Decay {
        #[state]
        #[param]
        c: f64,
        k: f64,
    }

    #[system]
    impl Decay {
        fn derivative(&self) -> DecayState {
            DecayState { c: -self.k * self.c }
        }
    }
}

mod param_without_jacobian {
    use odyn::system;

    #[system(jacobian = false)]
    struct Decay {
        #[state]
        c: f64,
        #[param]
        k: f64,
    }

    #[system]
    impl Decay {
        fn derivative(&self) -> DecayState {
            DecayState { c: -self.k * self.c }
        }
    }
}

mod param_through_an_opaque_call {
    use odyn::system;

    fn rate(k: f64) -> f64 {
        k * k
    }

    #[system]
    struct Decay {
        #[state]
        c: f64,
        #[param]
        k: f64,
    }

    #[system]
    impl Decay {
        fn derivative(&self) -> DecayState {
            DecayState { c: -rate(self.k) * self.c }
        }
    }
}

mod param_on_a_grid_model {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Heat {
        #[field]
        u: Grid,
        #[param]
        d: f64,
    }

    #[system]
    impl Heat {
        #[cell]
        fn rate(&self, u: Stencil) -> f64 {
            self.d * u.laplacian()
        }
    }
}

mod param_with_finite_differences {
    use odyn::system;

    // ∂f/∂p is generated exactly or not at all.
    #[system(jacobian = finite_differences)]
    struct Decay {
        #[state]
        c: f64,
        #[param]
        k: f64,
    }

    #[system]
    impl Decay {
        fn derivative(&self) -> DecayState {
            DecayState { c: -self.k * self.c }
        }
    }
}

fn main() {}
