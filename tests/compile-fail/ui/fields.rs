//! Rejected models: fields. One module per case, named for what it gets wrong;
//! each must give its own error at the offending token and nothing more. (One file per
//! topic: trybuild compiles each file as a crate, and one crate per case cost a minute.)
#![allow(dead_code)]

mod computed_array_length {
    use odyn::prelude::*;

    const N: usize = 4;

    #[system]
    pub struct Grid {
        #[state]
        pub u: [f64; N * N],
    }

    fn main() {}
}

mod generic_model {
    use odyn::prelude::*;

    #[system]
    pub struct Spring<T> {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
        pub k: T,
    }

    #[system]
    impl<T> Spring<T> {
        fn acceleration(&self) -> f64 {
            -self.x
        }
    }

    fn main() {
        let spring = Spring { x: 1.0, v: 0.0, k: 1.0 };
        let _ = spring.simulate().steps(10).run();
    }
}

mod const_parameter_not_usize {
    use odyn::prelude::*;

    #[system]
    pub struct Chain<const N: u32> {
        #[position]
        pub x: [f64; 3],
        #[velocity]
        pub v: [f64; 3],
    }

    #[system]
    impl<const N: u32> Chain<N> {
        fn acceleration(&self) -> [f64; 3] {
            self.x
        }
    }

    fn main() {
        let chain = Chain::<3> { x: [1.0; 3], v: [0.0; 3] };
        let _ = chain.simulate().steps(10).run();
    }
}

mod const_generic_impl_for_one_length {
    use odyn::prelude::*;

    #[system]
    pub struct Chain<const N: usize> {
        #[position]
        pub x: [f64; N],
        #[velocity]
        pub v: [f64; N],
        pub k: f64,
    }

    #[system]
    impl Chain<3> {
        fn acceleration(&self) -> [f64; 3] {
            [-self.k * self.x[0], 0.0, 0.0]
        }
    }

    fn main() {
        let chain = Chain::<3> { x: [1.0; 3], v: [0.0; 3], k: 1.0 };
        let _ = chain.simulate().steps(10).run();
    }
}

mod const_generic_with_param {
    use odyn::prelude::*;

    #[system]
    pub struct Chain<const N: usize> {
        #[position]
        pub x: [f64; N],
        #[velocity]
        pub v: [f64; N],
        #[param]
        pub k: f64,
    }

    #[system]
    impl<const N: usize> Chain<N> {
        fn acceleration(&self) -> [f64; N] {
            self.x.map(|x| -self.k * x)
        }
    }

    fn main() {
        let chain = Chain::<3> { x: [1.0; 3], v: [0.0; 3], k: 1.0 };
        let _ = chain.simulate().steps(10).run();
    }
}

mod const_generic_with_bad_field {
    use odyn::prelude::*;

    #[system]
    pub struct Rod<const N: usize> {
        #[state]
        pub u: [f32; N],
    }

    #[system]
    impl<const N: usize> Rod<N> {
        fn derivative(&self) -> RodState<N> {
            RodState { u: self.u }
        }
    }

    fn main() {
        let rod = Rod::<3> { u: [1.0; 3] };
        let _ = rod.simulate().steps(10).run();
    }
}

mod misspelt_role_attribute {
    use odyn::prelude::*;

    #[system]
    pub struct Spring {
        #[postion]
        pub x: f64,
        #[velocity]
        pub v: f64,
        pub k: f64,
    }

    #[system]
    impl Spring {
        fn acceleration(&self) -> f64 {
            -self.k * self.x
        }
    }

    fn main() {}
}

mod mixed_orders {
    use odyn::prelude::*;

    #[system]
    pub struct Confused {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
        #[state]
        pub charge: f64,
    }

    fn main() {}
}

mod no_state {
    use odyn::prelude::*;

    #[system]
    pub struct Parameters {
        pub k: f64,
        pub m: f64,
    }

    fn main() {}
}

mod position_without_velocity {
    use odyn::prelude::*;

    #[system]
    pub struct Pendulum {
        #[position]
        pub theta: f64,
        #[position]
        pub phi: f64,
        #[velocity]
        pub omega: f64,
    }

    fn main() {}
}

mod rejected_struct_used_elsewhere {
    use odyn::prelude::*;

    const N: usize = 3;

    // The struct is rejected; its impl block and the code that runs it still type-check, so the
    // field's error is the only one.
    #[system]
    pub struct Chain {
        #[state]
        pub x: [f64; N],
        pub k: f64,
    }

    #[system]
    impl Chain {
        fn derivative(&self) -> ChainState {
            ChainState { x: self.x.map(|x| -self.k * x) }
        }
    }

    fn main() {
        let chain = Chain { x: [1.0; N], k: 1.0 };
        let run = chain.simulate().steps(10).run().unwrap();
        let last: &ChainState = &run.last().state;
        println!("{last:?}");
    }
}

mod shape_mismatch {
    use odyn::prelude::*;

    #[system]
    pub struct Particle {
        #[position]
        pub r: Vector3<f64>,
        #[velocity]
        pub v: Vector2<f64>,
    }

    fn main() {}
}

mod tuple_struct {
    use odyn::prelude::*;

    #[system]
    pub struct Spring(f64, f64);

    fn main() {}
}

mod two_roles {
    use odyn::prelude::*;

    #[system]
    pub struct Spring {
        #[position]
        #[velocity]
        pub x: f64,
        #[velocity]
        pub v: f64,
    }

    fn main() {}
}

mod unknown_attribute {
    use odyn::prelude::*;

    // No derive on the struct could own `#[units]`, so it is an error, and the only one.
    #[system]
    pub struct Decay {
        #[state]
        pub x: f64,
        #[units(per_second)]
        pub k: f64,
    }

    #[system]
    impl Decay {
        fn derivative(&self) -> DecayState {
            DecayState { x: -self.k * self.x }
        }
    }

    fn main() {}
}

mod unsupported_type {
    use odyn::prelude::*;

    #[system]
    pub struct Spring {
        #[position]
        pub x: f32,
        #[velocity]
        pub v: f32,
    }

    fn main() {}
}

mod velocity_without_position {
    use odyn::prelude::*;

    #[system]
    pub struct Falling {
        #[velocity]
        pub v: f64,
        pub g: f64,
    }

    fn main() {}
}

mod arrays_of_vectors {
    use odyn::prelude::*;

    const N: usize = 4;

    // An array of vectors needs its length written out too; an array three deep is not a
    // state shape.
    #[system]
    pub struct Bodies {
        #[position]
        pub r: [Vector3<f64>; N],
        #[velocity]
        pub v: [[[f64; 2]; 2]; 2],
    }

    fn main() {}
}

fn main() {}
