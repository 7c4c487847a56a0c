//! The time derivative: exact where the time is read in the open, by differences through a
//! function odyn cannot see into, and through a shadowed or aliased time.

use crate::common;
use odyn::prelude::*;

/// A forced oscillator: ẍ = −x + A·sin(ωt)·e^(−t/τ). Its ∂f/∂t is generated exactly; a model
/// that reads the time through a function of the user's own gets the runtime's central
/// difference; an autonomous one a constant zero.
#[system]
#[derive(Clone, Copy, Debug)]
struct Forced {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    amplitude: f64,
    omega: f64,
    tau: f64,
}

#[system]
impl Forced {
    fn acceleration(&self, t: f64) -> f64 {
        let envelope = (-t / self.tau).exp();
        let drive = if t < 10.0 {
            (self.omega * t).sin()
        } else {
            0.0
        };
        -self.x + self.amplitude * drive * envelope * self.v.cos()
    }
}

fn pulse(t: f64) -> f64 {
    (-t * t).exp()
}

/// The time reaches f through `pulse`, a function odyn cannot see into.
#[system]
#[derive(Clone, Copy, Debug)]
struct Pulsed {
    #[state]
    y: f64,
}

#[system]
impl Pulsed {
    fn derivative(&self, t: f64) -> PulsedState {
        PulsedState {
            y: -self.y + pulse(t),
        }
    }
}

#[test]
fn the_time_derivative_is_exact_where_it_can_be() {
    let forced = Forced {
        x: 0.3,
        v: -0.2,
        amplitude: 1.5,
        omega: 2.0,
        tau: 4.0,
    };
    const { assert!(<Forced as odyn::Jacobian>::TIME_DEPENDENT) };
    let y = forced.state();
    for t in [0.0, 0.7, 3.1, 9.5, 12.0] {
        let mut dfdt = y;
        forced.time_derivative(t, &y, &mut dfdt);
        // Central difference in t of f(t, y), h = 1e-6.
        let (mut plus, mut minus) = (y, y);
        forced.derivative(t + 1e-6, &y, &mut plus);
        forced.derivative(t - 1e-6, &y, &mut minus);
        let fd = (plus.v - minus.v) / 2e-6;
        assert_eq!(dfdt.x, 0.0, "ẋ = v does not read t");
        assert!(
            (dfdt.v - fd).abs() < 1e-6 * (1.0 + fd.abs()),
            "t = {t}: {} vs {fd}",
            dfdt.v
        );
    }
    // Exact: at t = 0, ∂/∂t [A·sin(ωt)·e^(−t/τ)·cos v] = A·ω·cos(v).
    let mut dfdt = y;
    forced.time_derivative(0.0, &y, &mut dfdt);
    assert!((dfdt.v - 1.5 * 2.0 * (-0.2f64).cos()).abs() < 1e-15);

    let pulsed = Pulsed { y: 1.0 };
    let mut dfdt = pulsed.state();
    pulsed.time_derivative(0.5, &pulsed.state(), &mut dfdt);
    // d/dt e^(−t²) = −2t·e^(−t²).
    let exact = -2.0 * 0.5 * (-0.25f64).exp();
    assert!((dfdt.y - exact).abs() < 1e-8, "{} vs {exact}", dfdt.y);

    const { assert!(!<common::Lorenz as odyn::Jacobian>::TIME_DEPENDENT) };
}

/// The time shadowed by a shifted copy, and an alias of it passed to a function odyn cannot see
/// into: ẏ = −y + sin(t − t₀)·y + pulse(s), s = t.
#[system]
#[derive(Clone, Copy, Debug)]
struct Shifted {
    #[state]
    y: f64,
    t0: f64,
}

#[system]
impl Shifted {
    fn derivative(&self, t: f64) -> ShiftedState {
        let s = t;
        let kick = pulse(s);
        let t = t - self.t0;
        ShiftedState {
            y: -self.y + t.sin() * self.y + kick,
        }
    }
}

#[test]
fn a_shadowed_or_aliased_time_keeps_the_jacobian_and_time_derivative_right() {
    // The derivative code copies the time before the user's state-free lets run, so J reads
    // sin(t − t₀), not sin(t − 2t₀); and `pulse(s)` with s = t makes ∂f/∂t the runtime's
    // central difference (exact ∂f/∂t would have dropped pulse's part).
    let model = Shifted { y: 0.8, t0: 0.5 };
    let (t, y) = (1.3, model.state());
    let mut jacobian = model.jacobian_matrix(&y);
    model.jacobian(t, &y, &mut jacobian);
    let expected = -1.0 + (t - 0.5f64).sin();
    assert!(
        (jacobian[(0, 0)] - expected).abs() < 1e-15,
        "{}",
        jacobian[(0, 0)]
    );
    let mut dfdt = y;
    model.time_derivative(t, &y, &mut dfdt);
    // ∂f/∂t = cos(t − t₀)·y − 2t·e^(−t²).
    let exact = (t - 0.5f64).cos() * 0.8 - 2.0 * t * (-t * t).exp();
    assert!((dfdt.y - exact).abs() < 1e-8, "{} vs {exact}", dfdt.y);
}
