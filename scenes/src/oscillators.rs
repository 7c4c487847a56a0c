//! Springs: the tutorial's damped one and the undamped one whose exact solution every
//! integrator is measured against.

use odyn::prelude::*;

/// The tutorial's damped spring, m·ẍ = −k·x − b·ẋ, damping as a force.
#[system(integrator = SymplecticEuler, dt = 0.016)]
#[derive(Clone, Copy, Debug)]
pub struct Spring {
    /// Displacement from rest.
    #[position]
    pub x: f64,
    /// Velocity.
    #[velocity]
    pub v: f64,
    /// Stiffness k.
    pub k: f64,
    /// Damping coefficient b.
    pub b: f64,
    /// Mass m.
    pub m: f64,
}

#[system]
impl Spring {
    /// The spring the checks and benches share: k = 50, b = 0.5, m = 1, released from x = 1 at
    /// rest (ω₀ = √50 ≈ 7.07 rad/s, damping ratio 0.035).
    pub fn released() -> Self {
        Spring {
            x: 1.0,
            v: 0.0,
            k: 50.0,
            b: 0.5,
            m: 1.0,
        }
    }

    /// The spring's force over its mass.
    pub fn acceleration(&self) -> f64 {
        (-self.k * self.x - self.b * self.v) / self.m
    }

    /// Kinetic plus elastic energy, ½m·v² + ½k·x².
    pub fn energy(&self) -> f64 {
        0.5 * self.m * self.v * self.v + 0.5 * self.k * self.x * self.x
    }
}

/// The undamped spring, m·ẍ = −k·x: x = x₀·cos(ωt) with ω = √(k/m), and its force never reads
/// the velocity, so position Verlet takes it.
#[system]
#[derive(Clone, Copy, Debug)]
pub struct UndampedSpring {
    /// Displacement from rest.
    #[position]
    pub x: f64,
    /// Velocity.
    #[velocity]
    pub v: f64,
    /// Stiffness k.
    pub k: f64,
    /// Mass m.
    pub m: f64,
}

#[system]
impl UndampedSpring {
    fn acceleration(&self) -> f64 {
        -self.k / self.m * self.x
    }

    /// Kinetic plus elastic energy, ½m·v² + ½k·x².
    pub fn energy(&self) -> f64 {
        0.5 * self.m * self.v * self.v + 0.5 * self.k * self.x * self.x
    }
}
