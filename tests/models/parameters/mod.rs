//! ∂f/∂p generated for `#[param]` fields (`odyn::Parameters`): against central differences of f
//! in each parameter at random states, against the hand-derived values, and the parameter
//! vector's order, round trip and length check.

mod derivatives;
mod differences;
mod sensitivities;

use odyn::prelude::*;

/// The damped spring with its stiffness and damping as parameters: ∂a/∂k = −x/m, ∂a/∂b = −v/m.
#[system]
#[derive(Clone, Copy, Debug)]
pub struct FitSpring {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
    #[param]
    pub k: f64,
    #[param]
    pub b: f64,
    pub m: f64,
}

#[system]
impl FitSpring {
    fn acceleration(&self) -> f64 {
        (-self.k * self.x - self.b * self.v) / self.m
    }
}

/// Lorenz with all three coefficients as parameters.
#[system]
#[derive(Clone, Copy, Debug)]
pub struct FitLorenz {
    #[state]
    pub x: f64,
    #[state]
    pub y: f64,
    #[state]
    pub z: f64,
    #[param]
    pub sigma: f64,
    #[param]
    pub rho: f64,
    #[param]
    pub beta: f64,
}

#[system]
impl FitLorenz {
    fn derivative(&self) -> FitLorenzState {
        FitLorenzState {
            x: self.sigma * (self.y - self.x),
            y: self.x * (self.rho - self.z) - self.y,
            z: self.x * self.y - self.beta * self.z,
        }
    }
}

/// A reaction of order n with an Arrhenius rate a·exp(−e/T) that switches on at t = 1, the
/// parameters read through locals, a `powf`, an `exp`, a branch on the time and a branch on a
/// parameter; T is a plain (unmarked) parameter.
#[system]
#[derive(Clone, Copy, Debug)]
pub struct Arrhenius {
    #[state]
    pub c: f64,
    #[state]
    pub d: f64,
    #[param]
    pub a: f64,
    #[param]
    pub e: f64,
    #[param]
    pub n: f64,
    pub temperature: f64,
}

#[system]
impl Arrhenius {
    fn derivative(&self, t: f64) -> ArrheniusState {
        let rate = self.a * (-self.e / self.temperature).exp();
        let on = if t >= 1.0 { 1.0 } else { 0.5 };
        let order = if self.n > 1.0 { self.n } else { 2.0 - self.n };
        let r = on * rate * self.c.powf(order);
        ArrheniusState {
            c: -r,
            d: r - self.a * self.d,
        }
    }
}

/// Exponential decay ċ = −k·c with k and the initial value: c = c₀e^{−kt}, ∂c/∂k = −t·c₀e^{−kt},
/// ∂c/∂c₀ = e^{−kt} (differentiating the closed form).
#[system]
#[derive(Clone, Copy, Debug)]
pub struct Decay {
    #[state]
    pub c: f64,
    #[param]
    pub k: f64,
}

#[system]
impl Decay {
    fn derivative(&self) -> DecayState {
        DecayState {
            c: -self.k * self.c,
        }
    }
}
