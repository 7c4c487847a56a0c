//! Rejected models: grids. One module per case, named for what it gets wrong;
//! each must give its own error at the offending token and nothing more. (One file per
//! topic: trybuild compiles each file as a crate, and one crate per case cost a minute.)
#![allow(dead_code)]

mod cell_matches_on_state {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Heat {
        #[field]
        u: Grid,
        d: f64,
    }

    #[system]
    impl Heat {
        #[cell]
        fn rate(&self, u: Stencil) -> f64 {
            match u.c > 0.5 { true => self.d * u.laplacian(), false => 0.0 }
        }
    }

    fn main() {}
}

mod cell_reads_grid_through_self {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Brusselator {
        #[field]
        u: Grid,
        #[field]
        v: Grid,
        a: f64,
    }

    #[system]
    impl Brusselator {
        #[cell]
        fn rate(&self, u: Stencil, v: Stencil) -> [f64; 2] {
            [u.c - self.u.values()[0], v.c * self.a]
        }
    }

    fn main() {}
}

mod field_not_a_grid {
    use odyn::grid::Stencil;
    use odyn::system;

    #[system]
    struct Heat {
        #[field]
        u: Vec<f64>,
        d: f64,
    }

    #[system]
    impl Heat {
        #[cell]
        fn rate(&self, u: Stencil) -> f64 {
            self.d * u.laplacian()
        }
    }

    fn main() {}
}

mod field_with_arguments {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Heat {
        #[field(periodic)]
        u: Grid,
        d: f64,
    }

    #[system]
    impl Heat {
        #[cell]
        fn rate(&self, u: Stencil) -> f64 {
            self.d * u.laplacian()
        }
    }

    fn main() {}
}

mod misspelt_cell_attribute {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Heat {
        #[field]
        u: Grid,
        d: f64,
    }

    #[system]
    impl Heat {
        #[cel]
        fn rate(&self, u: Stencil) -> f64 {
            self.d * u.laplacian()
        }
    }

    fn main() {}
}

mod misspelt_field_attribute {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Heat {
        #[feild]
        u: Grid,
        d: f64,
    }

    #[system]
    impl Heat {
        #[cell]
        fn rate(&self, u: Stencil) -> f64 {
            self.d * u.laplacian()
        }
    }

    fn main() {}
}

mod no_cell {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Brusselator {
        #[field]
        u: Grid,
        #[field]
        v: Grid,
        a: f64,
    }

    #[system]
    impl Brusselator {
        fn rate(&self, u: Stencil, v: Stencil) -> [f64; 2] {
            [u.c, v.c * self.a]
        }
    }

    fn main() {}
}

mod second_order_method {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system(integrator = VelocityVerlet, dt = 0.1)]
    struct Heat {
        #[field]
        u: Grid,
        d: f64,
    }

    #[system]
    impl Heat {
        #[cell]
        fn rate(&self, u: Stencil) -> f64 {
            self.d * u.laplacian()
        }
    }

    fn main() {}
}

mod stencil_method {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Brusselator {
        #[field]
        u: Grid,
        #[field]
        v: Grid,
        a: f64,
    }

    #[system]
    impl Brusselator {
        #[cell]
        fn rate(&self, u: Stencil, v: Stencil) -> [f64; 2] {
            [u.gradient(), v.c * self.a]
        }
    }

    fn main() {}
}

mod stencil_not_a_field {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Brusselator {
        #[field]
        u: Grid,
        #[field]
        v: Grid,
        a: f64,
    }

    #[system]
    impl Brusselator {
        #[cell]
        fn rate(&self, u: Stencil, w: Stencil) -> [f64; 2] {
            [u.c, w.c * self.a]
        }
    }

    fn main() {}
}

mod stencil_used_whole {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Brusselator {
        #[field]
        u: Grid,
        #[field]
        v: Grid,
        a: f64,
    }

    fn spread(s: Stencil) -> f64 {
        s.e - s.w
    }

    #[system]
    impl Brusselator {
        #[cell]
        fn rate(&self, u: Stencil, v: Stencil) -> [f64; 2] {
            [spread(u), v.c * self.a]
        }
    }

    fn main() {}
}

mod unknown_neighbour {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Brusselator {
        #[field]
        u: Grid,
        #[field]
        v: Grid,
        a: f64,
    }

    #[system]
    impl Brusselator {
        #[cell]
        fn rate(&self, u: Stencil, v: Stencil) -> [f64; 2] {
            [u.nn - u.c, v.c * self.a]
        }
    }

    // The model still type-checks where it is used: no follow-on errors.
    fn run(model: &Brusselator) {
        let _ = odyn::Simulate::simulate(model);
    }

    fn main() {
        let _ = run;
    }
}

mod wrong_return {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Brusselator {
        #[field]
        u: Grid,
        #[field]
        v: Grid,
        a: f64,
    }

    #[system]
    impl Brusselator {
        #[cell]
        fn rate(&self, u: Stencil, v: Stencil) -> f64 {
            u.c * v.c * self.a
        }
    }

    fn main() {}
}

mod place_argument_misnamed {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Heat {
        #[field]
        u: Grid,
        d: f64,
    }

    #[system]
    impl Heat {
        #[cell]
        fn rate(&self, u: Stencil, z: f64) -> f64 {
            self.d * u.laplacian() + z
        }
    }

    fn main() {}
}

fn main() {}

mod algebraic_grid_without_field {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Balance {
        #[field]
        u: Grid,
        #[algebraic]
        z: Grid,
    }

    #[system]
    impl Balance {
        #[cell]
        fn rate(&self, u: Stencil) -> f64 {
            -u.c
        }
    }

    fn main() {}
}

mod algebraic_grid_without_jacobian {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system(jacobian = false)]
    struct Balance {
        #[field]
        u: Grid,
        #[field]
        #[algebraic]
        z: Grid,
    }

    #[system]
    impl Balance {
        #[cell]
        fn rate(&self, u: Stencil, z: Stencil) -> [f64; 2] {
            [z.c - u.c, z.c - 2.0 * u.c]
        }
    }

    fn main() {}
}

mod algebraic_parameter_in_field_model {
    use odyn::grid::{Grid, Stencil};
    use odyn::system;

    #[system]
    struct Balance {
        #[field]
        u: Grid,
        #[algebraic]
        k: f64,
    }

    #[system]
    impl Balance {
        #[cell]
        fn rate(&self, u: Stencil) -> f64 {
            -self.k * u.c
        }
    }

    fn main() {}
}
