//! The one table of odyn's integration methods.
//!
//! [`for_each_method!`] hands every row to a macro of the caller's: `odyn-runtime` makes the
//! `Method` enum, `Method::ALL`, `Method::info`, the integrator modules, the run dispatch and
//! the stability rules from it, and this crate makes [`METHODS`], which the `#[system]` macro
//! reads to accept and check `integrator = Name`. Nothing else lists the methods, so adding an
//! integrator is its file (`runtime/src/integrators/<module>.rs`, plus a tableau file if it has
//! one) and one row here.
//!
//! A row is
//!
//! ```text
//! /// Doc comment of the `Method` variant (order and source).
//! Variant {
//!     module: file_name,          // runtime/src/integrators/file_name.rs defines `Variant`
//!     name: "snake_case",         // CSV files and the command line
//!     label: "Chart label",
//!     order: 4,                   // global order of accuracy
//!     adaptive: false,            // estimates its error, so can run to tolerances
//!     needs: Nothing,             // Nothing | Split | VelocityFree | Jacobian
//!     stability: RungeKutta,      // RungeKutta | Verlet | Composition | AStable
//! }
//! ```
//!
//! `stability` names the rule the stability explorer predicts limits by: `RungeKutta` reads
//! `tableau_polynomial()` from the integrator's module, `Composition` its `Weights` type,
//! `Verlet` is ω·dt < 2 and `AStable` any dt on a spectrum in the left half-plane.

#![no_std]

/// What a method needs of a model beyond f(t, y).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Needs {
    /// Nothing more.
    Nothing,
    /// A position/velocity split (`#[position]`/`#[velocity]` fields).
    Split,
    /// A split whose forces do not read velocities.
    VelocityFree,
    /// The generated Jacobian ∂f/∂y.
    Jacobian,
}

/// The facts of one row that the `#[system]` macro reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MethodRow {
    /// The `Method` variant, as `#[system(integrator = ...)]` spells it.
    pub variant: &'static str,
    /// The snake-case name.
    pub name: &'static str,
    /// Whether it estimates its error (so `rtol`/`atol` apply to it).
    pub adaptive: bool,
    /// What it needs of a model.
    pub needs: Needs,
}

/// Calls `$callback! { [$extra…] rows… }` with every method's row, in the order of
/// `Method::ALL`. `$callback` must be a `macro_rules!` macro in scope where this is invoked;
/// `$extra` tokens are passed through first, in brackets. Each row reaches it as
///
/// ```text
/// #[doc = …]… Variant module "name" "label" order adaptive Needs Stability;
/// ```
///
/// so a callback matches them all with
/// `$($(#[$doc:meta])* $variant:ident $module:ident $name:literal $label:literal $order:literal
/// $adaptive:literal $needs:ident $stability:ident;)*`.
#[macro_export]
macro_rules! for_each_method {
    ($callback:ident $(, $extra:tt)*) => {
        $crate::__positional! {
            $callback [$($extra)*]
            /// Forward Euler, order 1; gains energy on oscillators (Hairer, Lubich & Wanner
            /// 2006, §I.1).
            ExplicitEuler {
                module: explicit_euler, name: "explicit_euler", label: "Explicit Euler",
                order: 1, adaptive: false, needs: Nothing, stability: RungeKutta,
            }
            /// Semi-implicit (symplectic) Euler, velocity first, order 1; bounded energy
            /// (HLW 2006, §I.1.2).
            SymplecticEuler {
                module: symplectic_euler, name: "symplectic_euler", label: "Symplectic Euler",
                order: 1, adaptive: false, needs: Split, stability: Verlet,
            }
            /// Position (Störmer) Verlet, order 2; needs velocity-free forces (Verlet 1967).
            PositionVerlet {
                module: position_verlet, name: "position_verlet", label: "Position Verlet",
                order: 2, adaptive: false, needs: VelocityFree, stability: Verlet,
            }
            /// Velocity Verlet, order 2; bounded energy (Swope et al. 1982).
            VelocityVerlet {
                module: velocity_verlet, name: "velocity_verlet", label: "Velocity Verlet",
                order: 2, adaptive: false, needs: Split, stability: Verlet,
            }
            /// Leapfrog, kick-drift-kick, order 2; bounded energy (HLW 2006, §I.3.1).
            Leapfrog {
                module: leapfrog, name: "leapfrog", label: "Leapfrog",
                order: 2, adaptive: false, needs: Split, stability: Verlet,
            }
            /// Yoshida's composition of three leapfrog substeps, order 4; bounded energy
            /// (Yoshida 1990). Needs velocity-free forces.
            Yoshida4 {
                module: yoshida4, name: "yoshida4", label: "Yoshida 4",
                order: 4, adaptive: false, needs: VelocityFree, stability: Composition,
            }
            /// Yoshida's composition of seven leapfrog substeps (solution A), order 6; bounded
            /// energy (Yoshida 1990). Needs velocity-free forces.
            Yoshida6 {
                module: yoshida6, name: "yoshida6", label: "Yoshida 6",
                order: 6, adaptive: false, needs: VelocityFree, stability: Composition,
            }
            /// Kahan & Li's optimised composition of nine leapfrog substeps, order 6; bounded
            /// energy (Kahan & Li 1997). Needs velocity-free forces.
            KahanLi6 {
                module: kahan_li6, name: "kahan_li6", label: "Kahan–Li 6",
                order: 6, adaptive: false, needs: VelocityFree, stability: Composition,
            }
            /// Classical fourth-order Runge–Kutta, order 4; slow secular energy drift
            /// (Kutta 1901).
            Rk4 {
                module: rk4, name: "rk4", label: "RK4",
                order: 4, adaptive: false, needs: Nothing, stability: RungeKutta,
            }
            /// Implicit (backward) Euler with Newton's method, order 1; A-stable, loses energy
            /// (Hairer & Wanner 1996, §IV.3). Needs the generated Jacobian.
            ImplicitEuler {
                module: implicit_euler, name: "implicit_euler", label: "Implicit Euler",
                order: 1, adaptive: false, needs: Jacobian, stability: AStable,
            }
            /// Tsitouras' Runge–Kutta pair, order 5(4), adaptive, dense output of order 4
            /// (Tsitouras 2011).
            Tsit5 {
                module: tsit5, name: "tsit5", label: "Tsit5",
                order: 5, adaptive: true, needs: Nothing, stability: RungeKutta,
            }
            /// Dormand & Prince's order-8 method with Hairer's 8(5,3) error estimate, adaptive,
            /// dense output of order 7 (Hairer, Nørsett & Wanner 1993, §II.10).
            Dop853 {
                module: dop853, name: "dop853", label: "DOP853",
                order: 8, adaptive: true, needs: Nothing, stability: RungeKutta,
            }
            /// The modified Rosenbrock method of MATLAB's `ode23s`, order 2(3), L-stable,
            /// adaptive, for stiff problems at loose tolerances (Shampine & Reichelt 1997).
            /// Needs the generated Jacobian.
            Rosenbrock23 {
                module: rosenbrock23, name: "rosenbrock23", label: "Rosenbrock23",
                order: 2, adaptive: true, needs: Jacobian, stability: AStable,
            }
            /// Steinebach's Rosenbrock–Wanner method, order 5(4), stiffly accurate, L-stable,
            /// adaptive, dense output of order 4 (Steinebach 2023). Needs the generated
            /// Jacobian.
            Rodas5P {
                module: rodas5p, name: "rodas5p", label: "Rodas5P",
                order: 5, adaptive: true, needs: Jacobian, stability: AStable,
            }
            /// The variable-order (1–5), variable-step numerical differentiation formulas of
            /// MATLAB's `ode15s` as SciPy's `BDF` implements them, with the Jacobian and its
            /// factorization reused across steps; dense output of the step's order (Shampine &
            /// Reichelt 1997). Order 2 at a fixed step, where it stays at the A-stable orders
            /// 1 and 2. Needs the generated Jacobian.
            Bdf {
                module: bdf, name: "bdf", label: "BDF",
                order: 2, adaptive: true, needs: Jacobian, stability: AStable,
            }
        }
    };
}

/// Turns the named rows of [`for_each_method!`] into the positional form its callbacks match.
#[doc(hidden)]
#[macro_export]
macro_rules! __positional {
    (
        $callback:ident $extra:tt
        $(
            $(#[$doc:meta])*
            $variant:ident {
                module: $module:ident, name: $name:literal, label: $label:literal,
                order: $order:literal, adaptive: $adaptive:literal, needs: $needs:ident,
                stability: $stability:ident,
            }
        )*
    ) => {
        $callback! {
            $extra
            $(
                $(#[$doc])* $variant $module $name $label $order $adaptive $needs $stability;
            )*
        }
    };
}

macro_rules! rows {
    (
        [$($extra:tt)*]
        $(
            $(#[$doc:meta])* $variant:ident $module:ident $name:literal $label:literal
            $order:literal $adaptive:literal $needs:ident $stability:ident;
        )*
    ) => {
        /// Every method's row, in the order of `Method::ALL`.
        pub const METHODS: &[MethodRow] = &[
            $(MethodRow {
                variant: stringify!($variant),
                name: $name,
                adaptive: $adaptive,
                needs: Needs::$needs,
            },)*
        ];
    };
}

for_each_method!(rows);
