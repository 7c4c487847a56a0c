//! The models the benches share: each bench compares these against hand-written arithmetic or
//! peer crates, so they must be the same models everywhere.
#![allow(
    dead_code,
    reason = "each bench uses a different subset of these models"
)]

use odyn::prelude::*;

/// The tutorial's damped spring, m·ẍ = −k·x − b·ẋ.
#[system]
#[derive(Clone, Copy)]
pub struct Spring {
    /// Displacement.
    #[position]
    pub x: f64,
    /// Velocity.
    #[velocity]
    pub v: f64,
    /// Stiffness.
    pub k: f64,
    /// Damping coefficient.
    pub b: f64,
    /// Mass.
    pub m: f64,
}

#[system]
impl Spring {
    fn acceleration(&self) -> f64 {
        (-self.k * self.x - self.b * self.v) / self.m
    }
}

/// The undamped spring, m·ẍ = −k·x, for position Verlet (its force must not read v).
#[system]
#[derive(Clone, Copy)]
pub struct Undamped {
    /// Displacement.
    #[position]
    pub x: f64,
    /// Velocity.
    #[velocity]
    pub v: f64,
    /// Stiffness.
    pub k: f64,
    /// Mass.
    pub m: f64,
}

#[system]
impl Undamped {
    fn acceleration(&self) -> f64 {
        -self.k * self.x / self.m
    }
}

/// The planar Kepler problem, r̈ = −GM·r/|r|³.
#[system]
#[derive(Clone, Copy)]
pub struct Kepler {
    /// Position.
    #[position]
    pub r: Vector2<f64>,
    /// Velocity.
    #[velocity]
    pub v: Vector2<f64>,
    /// Gravitational parameter.
    pub gm: f64,
}

#[system]
impl Kepler {
    fn acceleration(&self) -> Vector2<f64> {
        -self.gm * self.r / self.r.norm().powi(3)
    }
}

/// The Lorenz system.
#[system]
#[derive(Clone, Copy)]
pub struct Lorenz {
    /// x
    #[state]
    pub x: f64,
    /// y
    #[state]
    pub y: f64,
    /// z
    #[state]
    pub z: f64,
    /// σ
    pub sigma: f64,
    /// ρ
    pub rho: f64,
    /// β
    pub beta: f64,
}

#[system]
impl Lorenz {
    fn derivative(&self) -> LorenzState {
        LorenzState {
            x: self.sigma * (self.y - self.x),
            y: self.x * (self.rho - self.z) - self.y,
            z: self.x * self.y - self.beta * self.z,
        }
    }
}

/// The van der Pol oscillator, stiff for large μ.
#[system]
#[derive(Clone, Copy)]
pub struct VanDerPol {
    /// Position-like variable.
    #[state]
    pub y1: f64,
    /// Its rate.
    #[state]
    pub y2: f64,
    /// Stiffness parameter μ.
    pub mu: f64,
}

#[system]
impl VanDerPol {
    fn derivative(&self) -> VanDerPolState {
        VanDerPolState {
            y1: self.y2,
            y2: self.mu * (1.0 - self.y1 * self.y1) * self.y2 - self.y1,
        }
    }
}
