//! Forward sensitivities across an event that changes the state: a ball falling under `#[param]
//! g` and bouncing with v ← −0.8·v. The fourth hardening probe found ∂(y, v)/∂g = (−2.000,
//! −2.000) at t = 2 where central differences of whole solves give (0.570, −0.715): the
//! sensitivities did not jump at the bounces. The reference here is the closed form of the
//! bouncing motion, differentiated by a central difference in g (and in the drop height).

use odyn::Event;
use odyn::prelude::*;
use odyn::sensitivity::{Sensitive, SensitivityState};

/// A ball under gravity g, its height y above the ground.
#[system]
#[derive(Clone, Copy, Debug)]
struct Drop {
    #[position]
    y: f64,
    #[velocity]
    v: f64,
    #[param]
    g: f64,
}

#[system]
impl Drop {
    fn acceleration(&self) -> f64 {
        -self.g
    }
}

/// Restitution.
const E: f64 = 0.8;

/// (y, v) at t of a ball dropped from rest at height h under gravity g, bouncing with
/// restitution E: it first lands at τ₁ = √(2h/g) at speed √(2gh); after bounce k it leaves at
/// vₖ = Eᵏ√(2gh) and lands again 2vₖ/g later.
fn closed_form(t: f64, g: f64, h: f64) -> (f64, f64) {
    let mut tau = (2.0 * h / g).sqrt();
    if t < tau {
        return (h - 0.5 * g * t * t, -g * t);
    }
    let mut speed = E * (2.0 * g * h).sqrt();
    loop {
        let next = tau + 2.0 * speed / g;
        if t < next {
            let s = t - tau;
            return (speed * s - 0.5 * g * s * s, speed - g * s);
        }
        tau = next;
        speed *= E;
    }
}

#[test]
fn sensitivities_jump_at_a_bounce() {
    let (g, h) = (9.81, 1.0);
    let ball = Drop { y: h, v: 0.0, g };
    let sensitive = Sensitive::with_initial_state(&ball);
    let bounce = Event::crossing("ground", |_, s: &SensitivityState| s.state()[0])
        .falling()
        .change(|_, s: &mut SensitivityState| s.as_mut_slice()[1] *= -E);
    let run = sensitive
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-11, 1e-13)
        .duration(2.0)
        .event(bounce)
        .run()
        .unwrap();
    // Three bounces before t = 2 (at 0.45, 1.17 and 1.75 s).
    assert_eq!(run.events.len(), 3);
    let last = &run.last().state;
    let s = last.sensitivities();
    // Central differences of the closed form: truncation ~1e-12, rounding ~1e-10.
    let d = 1e-5;
    let by_g = |i: usize| {
        let (plus, minus) = (closed_form(2.0, g + d, h), closed_form(2.0, g - d, h));
        [
            (plus.0 - minus.0) / (2.0 * d),
            (plus.1 - minus.1) / (2.0 * d),
        ][i]
    };
    let by_h = |i: usize| {
        let (plus, minus) = (closed_form(2.0, g, h + d), closed_form(2.0, g, h - d));
        [
            (plus.0 - minus.0) / (2.0 * d),
            (plus.1 - minus.1) / (2.0 * d),
        ][i]
    };
    for i in 0..2 {
        // Column 0 is ∂/∂g, column 1 ∂/∂y₀ (the drop height), column 2 ∂/∂v₀ (not checked).
        for (column, expected) in [(0, by_g(i)), (1, by_h(i))] {
            assert!(
                (s[(i, column)] - expected).abs() < 1e-6 * expected.abs().max(1.0),
                "∂{}/∂{}: {} against the closed form's {expected}",
                ["y", "v"][i],
                last.columns()[column],
                s[(i, column)]
            );
        }
    }
    let (y, v) = closed_form(2.0, g, h);
    assert!((last.state()[0] - y).abs() < 1e-8 && (last.state()[1] - v).abs() < 1e-8);
}
