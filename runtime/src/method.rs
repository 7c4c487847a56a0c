//! [`Method`]: the run-time choice of integrator, with what each one needs and promises.

use std::fmt;
use std::str::FromStr;

use crate::Error;

/// An integration method, chosen at run time.
///
/// The core is statically dispatched (see [`crate::integrators`]); this enum is the edge where a
/// user, a CLI flag or an attribute picks one. Each variant documents its order and source.
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
    /// Classical fourth-order Runge–Kutta, order 4; slow secular energy drift (Kutta 1901).
    Rk4,
    /// Implicit (backward) Euler with Newton's method, order 1; A-stable, loses energy
    /// (Hairer & Wanner 1996, §IV.3). Needs the generated Jacobian.
    ImplicitEuler,
}

impl Method {
    /// Every method, in the order of the comparison table.
    pub const ALL: [Method; 7] = [
        Method::ExplicitEuler,
        Method::SymplecticEuler,
        Method::PositionVerlet,
        Method::VelocityVerlet,
        Method::Leapfrog,
        Method::Rk4,
        Method::ImplicitEuler,
    ];

    /// The snake-case name used in CSV files and on the command line (`symplectic_euler`).
    pub const fn name(self) -> &'static str {
        match self {
            Method::ExplicitEuler => "explicit_euler",
            Method::SymplecticEuler => "symplectic_euler",
            Method::PositionVerlet => "position_verlet",
            Method::VelocityVerlet => "velocity_verlet",
            Method::Leapfrog => "leapfrog",
            Method::Rk4 => "rk4",
            Method::ImplicitEuler => "implicit_euler",
        }
    }

    /// A label for charts and tables (`Symplectic Euler`).
    pub const fn label(self) -> &'static str {
        match self {
            Method::ExplicitEuler => "Explicit Euler",
            Method::SymplecticEuler => "Symplectic Euler",
            Method::PositionVerlet => "Position Verlet",
            Method::VelocityVerlet => "Velocity Verlet",
            Method::Leapfrog => "Leapfrog",
            Method::Rk4 => "RK4",
            Method::ImplicitEuler => "Implicit Euler",
        }
    }

    /// Global order of accuracy: the error at a fixed time falls as dtᵖ.
    pub const fn order(self) -> u32 {
        match self {
            Method::ExplicitEuler | Method::SymplecticEuler | Method::ImplicitEuler => 1,
            Method::PositionVerlet | Method::VelocityVerlet | Method::Leapfrog => 2,
            Method::Rk4 => 4,
        }
    }

    /// Whether the method needs a position/velocity split (a second-order model).
    pub const fn needs_second_order(self) -> bool {
        matches!(
            self,
            Method::SymplecticEuler
                | Method::PositionVerlet
                | Method::VelocityVerlet
                | Method::Leapfrog
        )
    }

    /// Whether the method needs the model's Jacobian.
    pub const fn needs_jacobian(self) -> bool {
        matches!(self, Method::ImplicitEuler)
    }

    /// Whether the method needs forces that do not read velocities.
    pub const fn needs_velocity_free_forces(self) -> bool {
        matches!(self, Method::PositionVerlet)
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
