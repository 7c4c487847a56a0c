//! [`Method`]: the run-time choice of integrator, with what each one needs and promises.

use std::fmt;
use std::str::FromStr;

use crate::Error;

/// An integration method, chosen at run time.
///
/// The core is statically dispatched (see [`crate::integrators`]); this enum is the edge where a
/// user, a CLI flag or an attribute picks one. Each variant documents its order and source; what
/// each needs and promises is one row of [`Method::info`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[non_exhaustive]
pub enum Method {
    /// Forward Euler, order 1; gains energy on oscillators (Hairer, Lubich & Wanner 2006, §I.1).
    ExplicitEuler,
    /// Semi-implicit (symplectic) Euler, velocity first, order 1; bounded energy (HLW 2006, §I.1.2).
    SymplecticEuler,
    /// Position (Störmer) Verlet, order 2; needs velocity-free forces (Verlet 1967).
    PositionVerlet,
    /// Velocity Verlet, order 2; bounded energy (Swope et al. 1982).
    VelocityVerlet,
    /// Leapfrog, kick-drift-kick, order 2; bounded energy (HLW 2006, §I.3.1).
    Leapfrog,
    /// Yoshida's composition of three leapfrog substeps, order 4; bounded energy (Yoshida 1990).
    /// Needs velocity-free forces.
    Yoshida4,
    /// Yoshida's composition of seven leapfrog substeps (solution A), order 6; bounded energy
    /// (Yoshida 1990). Needs velocity-free forces.
    Yoshida6,
    /// Kahan & Li's optimised composition of nine leapfrog substeps, order 6; bounded energy
    /// (Kahan & Li 1997). Needs velocity-free forces.
    KahanLi6,
    /// Classical fourth-order Runge–Kutta, order 4; slow secular energy drift (Kutta 1901).
    Rk4,
    /// Implicit (backward) Euler with Newton's method, order 1; A-stable, loses energy
    /// (Hairer & Wanner 1996, §IV.3). Needs the generated Jacobian.
    ImplicitEuler,
    /// Tsitouras' Runge–Kutta pair, order 5(4), adaptive, dense output of order 4
    /// (Tsitouras 2011).
    Tsit5,
    /// Dormand & Prince's order-8 method with Hairer's 8(5,3) error estimate, adaptive, dense
    /// output of order 7 (Hairer, Nørsett & Wanner 1993, §II.10).
    Dop853,
    /// The modified Rosenbrock method of MATLAB's `ode23s`, order 2(3), L-stable, adaptive, for
    /// stiff problems at loose tolerances (Shampine & Reichelt 1997). Needs the generated
    /// Jacobian.
    Rosenbrock23,
    /// Steinebach's Rosenbrock–Wanner method, order 5(4), stiffly accurate, L-stable, adaptive,
    /// dense output of order 4 (Steinebach 2023). Needs the generated Jacobian.
    Rodas5P,
    /// The variable-order (1–5), variable-step numerical differentiation formulas of MATLAB's
    /// `ode15s` as SciPy's `BDF` implements them, with the Jacobian and its factorization reused
    /// across steps; dense output of the step's order (Shampine & Reichelt 1997). Order 2 at a
    /// fixed step, where it stays at the A-stable orders. Needs the generated Jacobian.
    Bdf,
}

/// What a [`Method`] is and needs: one row of the table every part of odyn reads (the runner,
/// the stability explorer, work-precision studies, and the `#[system]` attribute's list, which a
/// test keeps in step with this one).
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

const fn row(
    name: &'static str,
    variant: &'static str,
    label: &'static str,
    order: u32,
    adaptive: bool,
    needs: (bool, bool, bool),
) -> MethodInfo {
    MethodInfo {
        name,
        variant,
        label,
        order,
        adaptive,
        needs_second_order: needs.0,
        needs_jacobian: needs.1,
        needs_velocity_free_forces: needs.2,
    }
}

/// Needs: (second order, Jacobian, velocity-free forces).
const NOTHING: (bool, bool, bool) = (false, false, false);
const SPLIT: (bool, bool, bool) = (true, false, false);
const JACOBIAN: (bool, bool, bool) = (false, true, false);
const VELOCITY_FREE: (bool, bool, bool) = (true, false, true);

impl Method {
    /// Every method, in the order of the comparison table.
    pub const ALL: [Method; 15] = [
        Method::ExplicitEuler,
        Method::SymplecticEuler,
        Method::PositionVerlet,
        Method::VelocityVerlet,
        Method::Leapfrog,
        Method::Yoshida4,
        Method::Yoshida6,
        Method::KahanLi6,
        Method::Rk4,
        Method::ImplicitEuler,
        Method::Tsit5,
        Method::Dop853,
        Method::Rosenbrock23,
        Method::Rodas5P,
        Method::Bdf,
    ];

    /// The method's row of the table.
    pub const fn info(self) -> MethodInfo {
        match self {
            Method::ExplicitEuler => row(
                "explicit_euler",
                "ExplicitEuler",
                "Explicit Euler",
                1,
                false,
                NOTHING,
            ),
            Method::SymplecticEuler => row(
                "symplectic_euler",
                "SymplecticEuler",
                "Symplectic Euler",
                1,
                false,
                SPLIT,
            ),
            Method::PositionVerlet => row(
                "position_verlet",
                "PositionVerlet",
                "Position Verlet",
                2,
                false,
                (true, false, true),
            ),
            Method::VelocityVerlet => row(
                "velocity_verlet",
                "VelocityVerlet",
                "Velocity Verlet",
                2,
                false,
                SPLIT,
            ),
            Method::Leapfrog => row("leapfrog", "Leapfrog", "Leapfrog", 2, false, SPLIT),
            Method::Yoshida4 => row("yoshida4", "Yoshida4", "Yoshida 4", 4, false, VELOCITY_FREE),
            Method::Yoshida6 => row("yoshida6", "Yoshida6", "Yoshida 6", 6, false, VELOCITY_FREE),
            Method::KahanLi6 => row(
                "kahan_li6",
                "KahanLi6",
                "Kahan–Li 6",
                6,
                false,
                VELOCITY_FREE,
            ),
            Method::Rk4 => row("rk4", "Rk4", "RK4", 4, false, NOTHING),
            Method::ImplicitEuler => row(
                "implicit_euler",
                "ImplicitEuler",
                "Implicit Euler",
                1,
                false,
                JACOBIAN,
            ),
            Method::Tsit5 => row("tsit5", "Tsit5", "Tsit5", 5, true, NOTHING),
            Method::Dop853 => row("dop853", "Dop853", "DOP853", 8, true, NOTHING),
            Method::Rosenbrock23 => row(
                "rosenbrock23",
                "Rosenbrock23",
                "Rosenbrock23",
                2,
                true,
                JACOBIAN,
            ),
            Method::Rodas5P => row("rodas5p", "Rodas5P", "Rodas5P", 5, true, JACOBIAN),
            // Variable order 1–5 when adaptive; a fixed step rises to order 2 only.
            Method::Bdf => row("bdf", "Bdf", "BDF", 2, true, JACOBIAN),
        }
    }

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

impl FromStr for Method {
    type Err = Error;

    /// Parses the snake-case [`Method::name`].
    fn from_str(s: &str) -> Result<Self, Error> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| {
                let names: Vec<_> = Method::ALL.iter().map(|m| m.name()).collect();
                Error::invalid(
                    "method",
                    format!("unknown method `{s}`; supported: {}", names.join(", ")),
                )
            })
    }
}
