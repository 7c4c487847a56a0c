//! The Lorenz system.

use odyn::prelude::*;

/// The Lorenz system (Lorenz 1963): x′ = σ(y − x), y′ = x(ρ − z) − y, z′ = xy − βz.
#[system(integrator = Rk4, dt = 0.01)]
#[derive(Clone, Copy, Debug)]
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

impl Lorenz {
    /// Lorenz's parameters σ = 10, ρ = 28, β = 8/3, from (1, 1, 1).
    pub fn classic() -> Self {
        Lorenz {
            x: 1.0,
            y: 1.0,
            z: 1.0,
            sigma: 10.0,
            rho: 28.0,
            beta: 8.0 / 3.0,
        }
    }
}
