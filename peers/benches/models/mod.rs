//! The models the peer benches share, each written once with `#[system]`; the benches give the
//! peers the same arithmetic on plain arrays.
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

/// The Arenstorf orbit: a satellite in the rotating frame of the Earth–Moon system, whose
/// solution is periodic (Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.0, eq. (0.1)). The same
/// arithmetic as odyn's test model and `scripts/reference_adaptive.py`.
#[system]
#[derive(Clone, Copy)]
pub struct Arenstorf {
    /// First coordinate in the rotating frame.
    #[position]
    pub y1: f64,
    /// Second coordinate.
    #[position]
    pub y2: f64,
    /// y1′.
    #[velocity]
    pub v1: f64,
    /// y2′.
    #[velocity]
    pub v2: f64,
    /// The Moon's mass fraction μ.
    pub mu: f64,
}

#[system]
impl Arenstorf {
    fn acceleration(&self) -> (f64, f64) {
        let mu = self.mu;
        let mup = 1.0 - self.mu;
        let d1 = ((self.y1 + mu).powi(2) + self.y2.powi(2)).powf(1.5);
        let d2 = ((self.y1 - mup).powi(2) + self.y2.powi(2)).powf(1.5);
        (
            self.y1 + 2.0 * self.v2 - mup * (self.y1 + mu) / d1 - mu * (self.y1 - mup) / d2,
            self.y2 - 2.0 * self.v1 - mup * self.y2 / d1 - mu * self.y2 / d2,
        )
    }
}

/// The Pleiades: seven bodies in the plane under Newtonian gravity, G = 1 (HNW I, §II.10,
/// eq. (10.12); problem PLEI of the Bari test set). Explicit methods only: the loops over the
/// bodies are outside what the Jacobian generator differentiates.
#[system(jacobian = false)]
#[derive(Clone, Copy)]
pub struct Pleiades {
    /// x coordinates.
    #[position]
    pub x: [f64; 7],
    /// y coordinates.
    #[position]
    pub y: [f64; 7],
    /// x velocities.
    #[velocity]
    pub u: [f64; 7],
    /// y velocities.
    #[velocity]
    pub v: [f64; 7],
    /// Masses.
    pub m: [f64; 7],
}

#[system]
impl Pleiades {
    /// Each pair once: the force is computed for i < j and applied to both bodies.
    fn acceleration(&self) -> ([f64; 7], [f64; 7]) {
        let mut ax = [0.0; 7];
        let mut ay = [0.0; 7];
        for i in 0..7 {
            for j in (i + 1)..7 {
                let dx = self.x[j] - self.x[i];
                let dy = self.y[j] - self.y[i];
                let r2 = dx * dx + dy * dy;
                let w = 1.0 / (r2 * r2.sqrt());
                ax[i] += self.m[j] * w * dx;
                ay[i] += self.m[j] * w * dy;
                ax[j] -= self.m[i] * w * dx;
                ay[j] -= self.m[i] * w * dy;
            }
        }
        (ax, ay)
    }
}
