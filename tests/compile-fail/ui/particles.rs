//! Rejected models: particles. One module per case, named for what it gets wrong;
//! each must give its own error at the offending token and nothing more. (One file per
//! topic: trybuild compiles each file as a crate, and one crate per case cost a minute.)
#![allow(dead_code)]

mod acceleration_in_particle_model {
    use odyn::particles::Spring;
    use odyn::prelude::*;

    #[system]
    struct Net {
        #[position]
        x: Vec<Vector3<f64>>,
        #[velocity]
        v: Vec<Vector3<f64>>,
        #[mass]
        m: Vec<f64>,
        springs: Vec<Spring>,
    }

    #[system]
    impl Net {
        #[particle]
        fn weight(&self, _x: Vector3<f64>) -> Vector3<f64> {
            Vector3::new(0.0, -9.81, 0.0)
        }

        fn acceleration(&self) -> Vector3<f64> {
            Vector3::zeros()
        }
    }

    fn main() {}
}

mod const_generic_particles {
    use odyn::particles::Spring;
    use odyn::prelude::*;

    #[system]
    struct Net<const N: usize> {
        #[position]
        x: Vec<Vector3<f64>>,
        #[velocity]
        v: Vec<Vector3<f64>>,
        #[mass]
        m: Vec<f64>,
        springs: Vec<Spring>,
    }

    #[system]
    impl<const N: usize> Net<N> {
        #[particle]
        fn weight(&self, _x: Vector3<f64>) -> Vector3<f64> {
            Vector3::new(0.0, -9.81, 0.0)
        }
    }

    fn main() {}
}

mod kernel_arity {
    use odyn::particles::Spring;
    use odyn::prelude::*;

    #[system]
    struct Net {
        #[position]
        x: Vec<Vector3<f64>>,
        #[velocity]
        v: Vec<Vector3<f64>>,
        #[mass]
        m: Vec<f64>,
        springs: Vec<Spring>,
    }

    #[system]
    impl Net {
        #[pair(springs)]
        fn spring(&self, s: &Spring, xa: Vector3<f64>, xb: Vector3<f64>, va: Vector3<f64>) -> Vector3<f64> {
            (xb - xa) * s.stiffness + va
        }
    }

    fn main() {}
}

mod kernel_call_as_condition_on_state {
    use odyn::particles::Spring;
    use odyn::prelude::*;

    #[system]
    struct Net {
        #[position]
        x: Vec<Vector3<f64>>,
        #[velocity]
        v: Vec<Vector3<f64>>,
        #[mass]
        m: Vec<f64>,
        springs: Vec<Spring>,
    }

    #[system]
    impl Net {
        #[pair(springs)]
        fn spring(&self, s: &Spring, xa: Vector3<f64>, xb: Vector3<f64>) -> Vector3<f64> {
            if (xb - xa).norm() > s.rest || xb.x.is_nan() { (xb - xa) * s.stiffness } else { Vector3::zeros() }
        }
    }

    fn main() {}
}

mod kernel_reads_state_through_self {
    use odyn::particles::Spring;
    use odyn::prelude::*;

    #[system]
    struct Net {
        #[position]
        x: Vec<Vector3<f64>>,
        #[velocity]
        v: Vec<Vector3<f64>>,
        #[mass]
        m: Vec<f64>,
        springs: Vec<Spring>,
    }

    #[system]
    impl Net {
        #[pair(springs)]
        fn spring(&self, s: &Spring, xa: Vector3<f64>, xb: Vector3<f64>) -> Vector3<f64> {
            (xb - xa) * s.stiffness + self.x[0]
        }
    }

    fn main() {}
}

mod links_not_a_vec {
    use odyn::particles::Spring;
    use odyn::prelude::*;

    #[system]
    struct Net {
        #[position]
        x: Vec<Vector3<f64>>,
        #[velocity]
        v: Vec<Vector3<f64>>,
        #[mass]
        m: Vec<f64>,
        springs: [Spring; 4],
    }

    #[system]
    impl Net {
        #[pair(springs)]
        fn spring(&self, s: &Spring, xa: Vector3<f64>, xb: Vector3<f64>) -> Vector3<f64> {
            (xb - xa) * s.stiffness
        }

        #[pair(ropes)]
        fn rope(&self, s: &Spring, xa: Vector3<f64>, xb: Vector3<f64>) -> Vector3<f64> {
            (xb - xa) * s.stiffness
        }
    }

    fn main() {}
}

mod missing_mass {
    use odyn::particles::Spring;
    use odyn::prelude::*;

    #[system]
    struct Beads {
        #[position]
        x: Vec<Vector3<f64>>,
        #[velocity]
        v: Vec<Vector3<f64>>,
        springs: Vec<Spring>,
    }

    fn main() {}
}

mod misspelt_kernel_attribute {
    use odyn::particles::Spring;
    use odyn::prelude::*;

    #[system]
    struct Beads {
        #[position]
        x: Vec<Vector3<f64>>,
        #[velocity]
        v: Vec<Vector3<f64>>,
        #[mass]
        m: Vec<f64>,
        springs: Vec<Spring>,
    }

    #[system]
    impl Beads {
        #[piar(springs)]
        fn spring(&self, s: &Spring, xa: Vector3<f64>, xb: Vector3<f64>) -> Vector3<f64> {
            let d = xb - xa;
            d / d.norm() * (s.stiffness * (d.norm() - s.rest))
        }
    }

    fn main() {}
}

mod misspelt_mass_attribute {
    use odyn::prelude::*;

    #[system]
    struct Beads {
        #[position]
        x: Vec<Vector3<f64>>,
        #[velocity]
        v: Vec<Vector3<f64>>,
        #[mas]
        m: Vec<f64>,
    }

    #[system]
    impl Beads {
        #[particle]
        fn gravity(&self, x: Vector3<f64>) -> Vector3<f64> {
            Vector3::new(0.0, 0.0, -9.81) + 0.0 * x
        }
    }

    fn main() {}
}

mod no_kernels {
    use odyn::particles::Spring;
    use odyn::prelude::*;

    #[system]
    struct Net {
        #[position]
        x: Vec<Vector3<f64>>,
        #[velocity]
        v: Vec<Vector3<f64>>,
        #[mass]
        m: Vec<f64>,
        springs: Vec<Spring>,
    }

    #[system]
    impl Net {
        fn potential(&self) -> f64 {
            0.0
        }
    }

    fn main() {}
}

mod position_verlet_with_damping_kernel {
    use odyn::prelude::*;

    #[system(integrator = PositionVerlet)]
    struct Net {
        #[position]
        x: Vec<Vector3<f64>>,
        #[velocity]
        v: Vec<Vector3<f64>>,
        #[mass]
        m: Vec<f64>,
    }

    #[system]
    impl Net {
        #[particle]
        fn drag(&self, _x: Vector3<f64>, v: Vector3<f64>) -> Vector3<f64> {
            -v
        }
    }

    fn main() {}
}

mod vec_of_f64 {
    use odyn::prelude::*;

    #[system]
    struct Beads {
        #[position]
        x: Vec<f64>,
        #[velocity]
        v: Vec<Vector3<f64>>,
        #[mass]
        m: Vec<f64>,
    }

    fn main() {}
}

mod finite_differences_on_particles {
    use odyn::nalgebra::Vector3;
    use odyn::system;

    // Particle and field models always get their sparse Jacobian from their kernels.
    #[system(jacobian = finite_differences)]
    struct Dust {
        #[position]
        x: Vec<Vector3<f64>>,
        #[velocity]
        v: Vec<Vector3<f64>>,
        #[mass]
        m: Vec<f64>,
    }

    #[system]
    impl Dust {
        #[particle]
        fn weight(&self, _x: Vector3<f64>) -> Vector3<f64> {
            Vector3::new(0.0, -9.81, 0.0)
        }
    }

    fn main() {}
}

fn main() {}

mod algebraic_in_particle_model {
    use odyn::particles::Spring;
    use odyn::prelude::*;

    #[system]
    struct Net {
        #[position]
        x: Vec<Vector3<f64>>,
        #[velocity]
        v: Vec<Vector3<f64>>,
        #[mass]
        m: Vec<f64>,
        #[algebraic]
        lambda: Vec<usize>,
        springs: Vec<Spring>,
    }

    #[system]
    impl Net {
        #[particle]
        fn weight(&self, _x: Vector3<f64>) -> Vector3<f64> {
            Vector3::new(0.0, -9.81, 0.0)
        }
    }

    fn main() {}
}
