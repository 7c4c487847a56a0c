//! Rejected models: placement. One module per case, named for what it gets wrong;
//! each must give its own error at the offending token and nothing more. (One file per
//! topic: trybuild compiles each file as a crate, and one crate per case cost a minute.)
#![allow(dead_code)]

mod impl_without_struct_attribute {
    use odyn::prelude::*;

    pub struct Spring {
        pub x: f64,
        pub v: f64,
    }

    #[system]
    impl Spring {
        fn acceleration(&self) -> f64 {
            -self.x
        }
    }

    fn main() {}
}

mod on_enum {
    use odyn::prelude::*;

    #[system]
    pub enum Phase {
        Solid,
        Liquid,
    }

    fn main() {}
}

mod trait_impl {
    use odyn::prelude::*;

    #[system]
    pub struct Spring {
        #[position]
        pub x: f64,
        #[velocity]
        pub v: f64,
    }

    #[system]
    impl Default for Spring {
        fn default() -> Self {
            Spring { x: 1.0, v: 0.0 }
        }
    }

    fn main() {}
}

fn main() {}
