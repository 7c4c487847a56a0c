//! The methods: [`Method`], the run-time choice of integrator, with what each one needs and
//! promises; and one zero-sized type per method ([`Rk4`], [`Rodas5P`], …, each a
//! [`MethodType`](crate::MethodType)), the
//! compile-time choice, for [`Simulation::run_with`](crate::Simulation::run_with).
//!
//! A program that runs a model with `.run()` dispatches on the [`Method`] at run time, so it
//! compiles every method the model can take — sixteen loops. One that runs it with
//! `.run_with::<method::Rk4>()` compiles one. For example,
//!
//! `spring.simulate().duration(1.0).run_with::<method::VelocityVerlet>()` (the guide's chapter
//! on choosing a method runs it).

use std::fmt;

/// Makes [`Method`], [`Method::ALL`] and [`Method::info`] from the rows of
/// `odyn_methods::for_each_method!`, the one table of methods.
macro_rules! define_methods {
    (
        []
        $(
            $(#[$doc:meta])* $variant:ident $module:ident $name:literal $label:literal
            $order:literal $adaptive:literal $needs:ident $stability:ident;
        )*
    ) => {
        /// An integration method, chosen at run time.
        ///
        /// The core is statically dispatched (see [`crate::integrators`]); this enum is the edge
        /// where a user, a CLI flag or an attribute picks one. Each variant documents its order
        /// and source; what each needs and promises is one row of [`Method::info`]. Variants,
        /// their docs and their rows come from the one table of methods (the `odyn-methods`
        /// crate).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        #[non_exhaustive]
        pub enum Method {
            $($(#[$doc])* $variant,)*
        }

        $(
            $(#[$doc])*
            ///
            /// The compile-time choice of this method: see [`MethodType`](crate::MethodType).
            #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
            pub struct $variant;
        )*

        impl Method {
            /// Every method, in the order of the comparison table.
            pub const ALL: [Method; [$(stringify!($variant)),*].len()] = [$(Method::$variant,)*];

            /// The method's row of the table.
            pub const fn info(self) -> MethodInfo {
                match self {
                    $(Method::$variant => MethodInfo {
                        name: $name,
                        variant: stringify!($variant),
                        label: $label,
                        order: $order,
                        adaptive: $adaptive,
                        needs_second_order: matches!(
                            odyn_methods::Needs::$needs,
                            odyn_methods::Needs::Split | odyn_methods::Needs::VelocityFree
                        ),
                        needs_jacobian: matches!(
                            odyn_methods::Needs::$needs,
                            odyn_methods::Needs::Jacobian
                        ),
                        needs_velocity_free_forces: matches!(
                            odyn_methods::Needs::$needs,
                            odyn_methods::Needs::VelocityFree
                        ),
                    },)*
                }
            }
        }
    };
}

odyn_methods::for_each_method!(define_methods);

/// What a [`Method`] is and needs: one row of the table every part of odyn reads (the runner,
/// the stability explorer, work-precision studies; the `#[system]` attribute reads the same
/// table).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MethodInfo {
    /// The snake-case name used in CSV files and on the command line (`symplectic_euler`).
    pub name: &'static str,
    /// The variant's name, as `#[system(integrator = ...)]` spells it (`SymplecticEuler`).
    pub variant: &'static str,
    /// A label for charts and tables (`Symplectic Euler`).
    pub label: &'static str,
    /// Global order of accuracy: the error at a fixed time falls as dtᵖ.
    pub order: u32,
    /// Whether it estimates its local error, so it can run with tolerances instead of a dt.
    pub adaptive: bool,
    /// Whether it needs a position/velocity split (a second-order model).
    pub needs_second_order: bool,
    /// Whether it needs the model's Jacobian.
    pub needs_jacobian: bool,
    /// Whether it needs forces that do not read velocities.
    pub needs_velocity_free_forces: bool,
}

impl Method {
    /// The snake-case name used in CSV files and on the command line (`symplectic_euler`).
    pub const fn name(self) -> &'static str {
        self.info().name
    }

    /// A label for charts and tables (`Symplectic Euler`).
    pub const fn label(self) -> &'static str {
        self.info().label
    }

    /// Global order of accuracy: the error at a fixed time falls as dtᵖ.
    pub const fn order(self) -> u32 {
        self.info().order
    }

    /// Whether the method estimates its error and so runs with tolerances by default.
    pub const fn is_adaptive(self) -> bool {
        self.info().adaptive
    }

    /// Whether the method needs a position/velocity split (a second-order model).
    pub const fn needs_second_order(self) -> bool {
        self.info().needs_second_order
    }

    /// Whether the method needs the model's Jacobian.
    pub const fn needs_jacobian(self) -> bool {
        self.info().needs_jacobian
    }

    /// Whether the method integrates M·y′ = f(t, y) with a mass matrix M ≠ I: a
    /// differential–algebraic model (`#[algebraic]` fields, or `fn mass`): the methods that
    /// solve a linear system each step, which then has M − c·J in place of I − c·J — the
    /// Rosenbrock methods (Hairer & Wanner, *Solving ODEs II*, §VI.4), BDF and implicit Euler.
    /// Explicit methods have no such system to put M in.
    pub const fn takes_mass_matrix(self) -> bool {
        matches!(
            self,
            Method::Rodas5P | Method::Rosenbrock23 | Method::Bdf | Method::ImplicitEuler
        )
    }

    /// Whether the method needs forces that do not read velocities.
    pub const fn needs_velocity_free_forces(self) -> bool {
        self.info().needs_velocity_free_forces
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The enum, its rows and the macro's list come from one table: the same variants, in the
    /// same order, with the same facts.
    #[test]
    fn the_enum_and_the_macro_read_the_same_table() {
        assert_eq!(Method::ALL.len(), odyn_methods::METHODS.len());
        for (method, row) in Method::ALL.iter().zip(odyn_methods::METHODS) {
            let info = method.info();
            assert_eq!(info.variant, row.variant);
            assert_eq!(info.name, row.name);
            assert_eq!(info.adaptive, row.adaptive);
            assert_eq!(
                info.needs_jacobian,
                row.needs == odyn_methods::Needs::Jacobian
            );
            assert_eq!(info.name.parse::<Method>().ok(), Some(*method));
        }
    }
}
