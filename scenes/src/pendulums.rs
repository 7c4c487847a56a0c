//! Pendulums: the double pendulum of the chaos demonstrations, and the damped pendulum the
//! `fit_pendulum` example fits.

use odyn::prelude::*;

/// The double pendulum: two point masses on massless rods, angles from the downward vertical;
/// the equations of motion from the Lagrangian (Levien & Tan, "Double pendulum: An experiment in
/// chaos", Am. J. Phys. 61 (1993) 1038).
#[system]
#[derive(Clone, Copy)]
pub struct DoublePendulum {
    /// Upper angle from the vertical (rad).
    #[position]
    pub theta1: f64,
    /// Lower angle from the vertical (rad).
    #[position]
    pub theta2: f64,
    /// Upper angular velocity (rad/s).
    #[velocity]
    pub omega1: f64,
    /// Lower angular velocity (rad/s).
    #[velocity]
    pub omega2: f64,
    /// Upper mass.
    pub m1: f64,
    /// Lower mass.
    pub m2: f64,
    /// Upper rod length.
    pub l1: f64,
    /// Lower rod length.
    pub l2: f64,
    /// Gravity.
    pub g: f64,
}

#[system]
impl DoublePendulum {
    /// The angular accelerations.
    pub fn acceleration(&self) -> (f64, f64) {
        let (m1, m2, l1, l2, g) = (self.m1, self.m2, self.l1, self.l2, self.g);
        let (w1, w2) = (self.omega1, self.omega2);
        let d = self.theta1 - self.theta2;
        let den = 2.0 * m1 + m2 - m2 * (2.0 * d).cos();
        let a1 = (-g * (2.0 * m1 + m2) * self.theta1.sin()
            - m2 * g * (self.theta1 - 2.0 * self.theta2).sin()
            - 2.0 * d.sin() * m2 * (w2 * w2 * l2 + w1 * w1 * l1 * d.cos()))
            / (l1 * den);
        let a2 = 2.0
            * d.sin()
            * (w1 * w1 * l1 * (m1 + m2)
                + g * (m1 + m2) * self.theta1.cos()
                + w2 * w2 * l2 * m2 * d.cos())
            / (l2 * den);
        (a1, a2)
    }

    /// Kinetic plus potential energy (conserved).
    pub fn energy(&self) -> f64 {
        let (m1, m2, l1, l2, g) = (self.m1, self.m2, self.l1, self.l2, self.g);
        let (w1, w2) = (self.omega1, self.omega2);
        let kinetic = 0.5 * m1 * l1 * l1 * w1 * w1
            + 0.5
                * m2
                * (l1 * l1 * w1 * w1
                    + l2 * l2 * w2 * w2
                    + 2.0 * l1 * l2 * w1 * w2 * (self.theta1 - self.theta2).cos());
        let potential = -(m1 + m2) * g * l1 * self.theta1.cos() - m2 * g * l2 * self.theta2.cos();
        kinetic + potential
    }
}

impl DoublePendulum {
    /// The `double_pendulum` example's: m₁ = m₂ = 1, l₁ = l₂ = 1, g = 9.81, released from rest at
    /// θ₁ = 2.0, θ₂ = 2.5 rad.
    pub fn released() -> Self {
        DoublePendulum {
            theta1: 2.0,
            theta2: 2.5,
            omega1: 0.0,
            omega2: 0.0,
            m1: 1.0,
            m2: 1.0,
            l1: 1.0,
            l2: 1.0,
            g: 9.81,
        }
    }
}

/// A damped pendulum, θ̈ = −ω²·sin θ − γ·θ̇: ω² = g/l and the damping rate γ are `#[param]`s, so
/// ∂f/∂p and the sensitivities to them are generated (the `fit_pendulum` example recovers them
/// from a noisy swing).
#[system]
#[derive(Clone, Copy, Debug)]
pub struct DampedPendulum {
    /// Angle from the downward vertical (rad).
    #[position]
    pub theta: f64,
    /// Angular velocity (rad/s).
    #[velocity]
    pub omega: f64,
    /// ω² = g/l (s⁻²).
    #[param]
    pub omega2: f64,
    /// Damping rate γ (s⁻¹).
    #[param]
    pub gamma: f64,
}

#[system]
impl DampedPendulum {
    fn acceleration(&self) -> f64 {
        -self.omega2 * self.theta.sin() - self.gamma * self.omega
    }
}

impl DampedPendulum {
    /// A 1 m pendulum (ω² = 9.81 s⁻²) damped at γ = 0.3 s⁻¹, released from rest at θ = 1 rad.
    pub fn released() -> Self {
        DampedPendulum {
            theta: 1.0,
            omega: 0.0,
            omega2: 9.81,
            gamma: 0.3,
        }
    }
}
