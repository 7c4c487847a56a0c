//! Models shared by the integration tests.
#![allow(
    dead_code,
    reason = "each test crate uses a different subset of these models"
)]

use odyn::prelude::*;

/// Least-squares slope of log(error) against log(dt): the observed order of convergence.
pub fn slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = points.iter().map(|(h, e)| (h.ln(), e.ln())).unzip();
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let cov: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let var: f64 = lx.iter().map(|x| (x - mx) * (x - mx)).sum();
    cov / var
}

/// Damped spring, m·ẍ = −k·x − b·ẋ (the tutorial's model).
#[system(integrator = SymplecticEuler, dt = 0.016)]
#[derive(Clone, Copy, Debug)]
pub struct Spring {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
    pub k: f64,
    pub b: f64,
    pub m: f64,
}

#[system]
impl Spring {
    pub fn acceleration(&self) -> f64 {
        (-self.k * self.x - self.b * self.v) / self.m
    }

    pub fn energy(&self) -> f64 {
        0.5 * self.m * self.v * self.v + 0.5 * self.k * self.x * self.x
    }
}

/// Undamped oscillator ẍ = −ω²x: its force never reads the velocity, so position Verlet takes it.
#[system(integrator = PositionVerlet)]
#[derive(Clone, Copy, Debug)]
pub struct Oscillator {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
    pub omega: f64,
}

#[system]
impl Oscillator {
    fn acceleration(&self) -> f64 {
        -self.omega * self.omega * self.x
    }

    /// Energy per unit mass.
    fn energy(&self) -> f64 {
        0.5 * self.v * self.v + 0.5 * self.omega * self.omega * self.x * self.x
    }
}

/// The Lorenz system (first-order).
#[system(integrator = Rk4, dt = 0.01)]
pub struct Lorenz {
    #[state]
    pub x: f64,
    #[state]
    pub y: f64,
    #[state]
    pub z: f64,
    pub sigma: f64,
    pub rho: f64,
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

/// Kepler problem in the plane, r̈ = −GM·r/|r|³, with vector state.
#[system(integrator = Leapfrog, dt = 0.01)]
pub struct Kepler {
    #[position]
    pub r: Vector2<f64>,
    #[velocity]
    pub v: Vector2<f64>,
    pub gm: f64,
}

#[system]
impl Kepler {
    fn acceleration(&self) -> Vector2<f64> {
        let r = self.r;
        -self.gm * r / r.norm().powi(3)
    }

    fn energy(&self) -> f64 {
        0.5 * self.v.norm_squared() - self.gm / self.r.norm()
    }
}

/// Two uncoupled oscillators as two position/velocity pairs, one driven by cos(t):
/// exercises tuple accelerations, array fields and the time argument.
#[system]
pub struct Pair {
    #[position]
    pub a: f64,
    #[position]
    pub b: [f64; 2],
    #[velocity]
    pub va: f64,
    #[velocity]
    pub vb: [f64; 2],
    pub drive: f64,
}

#[system]
impl Pair {
    fn acceleration(&self, t: f64) -> (f64, [f64; 2]) {
        (
            -self.a + self.drive * t.cos(),
            [-self.b[0], -4.0 * self.b[1]],
        )
    }
}

/// Simple pendulum θ̈ = −(g/L)·sin θ.
#[system(integrator = VelocityVerlet, dt = 0.01)]
pub struct Pendulum {
    #[position]
    pub theta: f64,
    #[velocity]
    pub omega: f64,
    pub g: f64,
    pub length: f64,
}

#[system]
impl Pendulum {
    fn acceleration(&self) -> f64 {
        -self.g / self.length * self.theta.sin()
    }

    fn energy(&self) -> f64 {
        0.5 * self.length * self.length * self.omega * self.omega
            + self.g * self.length * (1.0 - self.theta.cos())
    }
}

/// Van der Pol, y1′ = y2, y2′ = μ(1 − y1²)y2 − y1 (stiff for large μ).
#[system(integrator = ImplicitEuler)]
pub struct VanDerPol {
    #[state]
    pub y1: f64,
    #[state]
    pub y2: f64,
    pub mu: f64,
}

#[system]
impl VanDerPol {
    fn derivative(&self) -> VanDerPolState {
        VanDerPolState {
            y1: self.y2,
            y2: self.mu * (1.0 - self.y1.powi(2)) * self.y2 - self.y1,
        }
    }
}

/// Robertson's chemical kinetics (Robertson 1966), the classic stiff test problem.
#[system(integrator = ImplicitEuler)]
pub struct Robertson {
    #[state]
    pub a: f64,
    #[state]
    pub b: f64,
    #[state]
    pub c: f64,
}

#[system]
impl Robertson {
    fn derivative(&self) -> RobertsonState {
        let slow = 0.04 * self.a;
        let exchange = 1e4 * self.b * self.c;
        let fast = 3e7 * self.b * self.b;
        RobertsonState {
            a: -slow + exchange,
            b: slow - exchange - fast,
            c: fast,
        }
    }
}

/// A charged particle in 3-D: Kepler attraction plus a magnetic (Lorentz) force q·v × B,
/// exercising `Vector3`, `cross`, `normalize` and vector parameters.
#[system(integrator = Rk4, dt = 0.01)]
pub struct Charged {
    #[position]
    pub r: Vector3<f64>,
    #[velocity]
    pub v: Vector3<f64>,
    pub gm: f64,
    pub qb: Vector3<f64>,
}

#[system]
impl Charged {
    fn acceleration(&self, t: f64) -> Vector3<f64> {
        let distance = self.r.norm();
        let radial = self.r.normalize();
        let lorentz = self.v.cross(&self.qb) * (1.0 + 0.1 * t.sin());
        -self.gm / (distance * distance) * radial + lorentz
    }
}

/// A force odyn cannot differentiate (a branch on the state), opted out of the Jacobian.
#[system(integrator = SymplecticEuler, jacobian = false)]
pub struct NoJacobian {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
}

#[system]
impl NoJacobian {
    fn acceleration(&self) -> f64 {
        if self.x > 0.0 { -1.0 } else { 1.0 }
    }
}

/// Seventeen independent oscillators ẍᵢ = −ωᵢ²xᵢ with ωᵢ = i + 1: 34 state components, past the
/// 32 at which generated Jacobians move from the stack to faer.
#[system]
pub struct Bank {
    #[position]
    pub x: [f64; 17],
    #[velocity]
    pub v: [f64; 17],
}

#[system]
impl Bank {
    fn acceleration(&self) -> [f64; 17] {
        let x = self.x;
        [
            -x[0],
            -4.0 * x[1],
            -9.0 * x[2],
            -16.0 * x[3],
            -25.0 * x[4],
            -36.0 * x[5],
            -49.0 * x[6],
            -64.0 * x[7],
            -81.0 * x[8],
            -100.0 * x[9],
            -121.0 * x[10],
            -144.0 * x[11],
            -169.0 * x[12],
            -196.0 * x[13],
            -225.0 * x[14],
            -256.0 * x[15],
            -289.0 * x[16],
        ]
    }
}
