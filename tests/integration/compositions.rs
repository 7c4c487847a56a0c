//! The composition methods (Yoshida4, Yoshida6, Kahan–Li 6): measured orders, bounded energy over
//! a million steps, angular momentum to round-off, and the stability limits the explorer predicts.

use crate::common::{self, slope};

use std::f64::consts::TAU;

use odyn::prelude::*;
use odyn::stability::predicted_limit;

/// A driven oscillator ẍ = −x + cos 2t: the force reads the time, so each substep must evaluate
/// it at its own time.
#[system]
struct Driven {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
}

#[system]
impl Driven {
    fn acceleration(&self, t: f64) -> f64 {
        -self.x + (2.0 * t).cos()
    }
}

/// Kepler with e = 0.5, GM = 1, from pericentre (0.5, 0) with speed √3 (vis-viva with a = 1):
/// E = −1/2, L = 0.5·√3, period 2π, so after one period the exact state is the initial one.
fn kepler() -> common::Kepler {
    common::Kepler {
        r: Vector2::new(0.5, 0.0),
        v: Vector2::new(0.0, 3f64.sqrt()),
        gm: 1.0,
    }
}

/// Max-norm distance from the initial state after one period at `steps` steps per period.
fn period_error(method: Method, steps: u64) -> f64 {
    let model = kepler();
    let run = model
        .simulate()
        .integrator(method)
        .dt(TAU / steps as f64)
        .steps(steps)
        .record_every(u64::MAX)
        .run()
        .unwrap();
    let end = &run.last().state;
    (end.r - model.r).amax().max((end.v - model.v).amax())
}

/// Orders 4, 6 and 6 (Yoshida 1990; Kahan & Li 1997; HLW, *Geometric Numerical Integration*,
/// §V.3), within ±0.15, over step counts whose errors lie between ~1e-4 and ~1e-11 (above
/// round-off, inside the asymptotic range).
#[test]
fn compositions_have_their_orders_on_kepler() {
    for (method, order, steps) in [
        (Method::Yoshida4, 4.0, [400, 800, 1600, 3200]),
        (Method::Yoshida6, 6.0, [200, 400, 800, 1600]),
        (Method::KahanLi6, 6.0, [100, 200, 400, 800]),
    ] {
        let points: Vec<_> = steps
            .iter()
            .map(|&n| (TAU / n as f64, period_error(method, n)))
            .collect();
        let observed = slope(&points);
        eprintln!("{method}: {points:?}, observed order {observed:.3}");
        assert!(
            (observed - order).abs() <= 0.15,
            "{method}: observed order {observed:.3}, expected {order}"
        );
    }
}

/// At equal force evaluations the optimised Kahan–Li weights beat Yoshida's sixth-order ones:
/// 9 evaluations a step at 700 steps a period against 7 at 900 (6300 evaluations each).
#[test]
fn kahan_li_beats_yoshida6_at_equal_work() {
    let kahan_li = period_error(Method::KahanLi6, 700);
    let yoshida = period_error(Method::Yoshida6, 900);
    eprintln!("Kahan–Li 6: {kahan_li:e}, Yoshida 6: {yoshida:e}");
    assert!(kahan_li < yoshida, "{kahan_li:e} ≥ {yoshida:e}");
}

/// Symplectic: the Kepler energy stays within a band over 10⁶ steps (≈ 1600 orbits at 628 steps
/// an orbit) with no drift — the last tenth of the run spans the same band as the first — and the
/// angular momentum, which every leapfrog substep conserves exactly in exact arithmetic (central
/// force), to round-off: |ΔL| ≤ 1e-11 after 10⁶ steps.
#[test]
fn compositions_bound_the_energy_and_conserve_angular_momentum() {
    let model = kepler();
    let l0 = model.r.x * model.v.y - model.r.y * model.v.x;
    for method in [Method::Yoshida4, Method::Yoshida6, Method::KahanLi6] {
        let run = model
            .simulate()
            .integrator(method)
            .dt(0.01)
            .steps(1_000_000)
            .record_every(997)
            .run()
            .unwrap();
        let energies: Vec<f64> = run
            .samples
            .iter()
            .map(|s| s.energy.unwrap() + 0.5)
            .collect();
        let tenth = energies.len() / 10;
        let band = |e: &[f64]| e.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let (first, last) = (
            band(&energies[..tenth]),
            band(&energies[energies.len() - tenth..]),
        );
        eprintln!("{method}: |E − E₀| ≤ {first:e} (first tenth), {last:e} (last tenth)");
        assert!(
            first < 1e-5 && last <= 1.5 * first + 1e-14,
            "{method}: {first:e}, {last:e}"
        );
        for s in &run.samples {
            let l = s.state.r.x * s.state.v.y - s.state.r.y * s.state.v.x;
            assert!(
                (l - l0).abs() <= 1e-11,
                "{method}: ΔL = {:e} at step {}",
                l - l0,
                s.step
            );
        }
    }
}

/// The stability explorer's prediction on ẍ = −ω²x (from the composed one-step matrix) is the
/// measured limit: bounded at 0.99× the predicted ω·h for 10⁴ steps, diverging at 1.01×.
#[test]
fn composition_limits_are_predicted_and_measured() {
    let osc = common::Oscillator {
        x: 1.0,
        v: 0.0,
        omega: 1.0,
    };
    for method in [Method::Yoshida4, Method::Yoshida6, Method::KahanLi6] {
        let limit = predicted_limit(&osc, 0.0, &osc.state(), method).unwrap();
        eprintln!("{method}: predicted ωh limit {limit:.6}");
        assert!(limit > 0.5 && limit < 3.0, "{method}: {limit}");
        let stable = osc
            .simulate()
            .integrator(method)
            .dt(0.99 * limit)
            .steps(10_000)
            .record_every(u64::MAX)
            .run()
            .unwrap();
        assert!(stable.last().state.x.abs() < 10.0, "{method} at 0.99×");
        let unstable = osc
            .simulate()
            .integrator(method)
            .dt(1.01 * limit)
            .steps(100_000)
            .run();
        assert!(
            matches!(unstable, Err(odyn::Error::Diverged { .. })),
            "{method} at 1.01×: {unstable:?}"
        );
    }
}

/// With a time-dependent force the orders hold too: from x = 1, v = 0 the exact solution of
/// ẍ = −x + cos 2t is x = (4/3)·cos t − (1/3)·cos 2t (undetermined coefficients). Errors at
/// t = 10 over four step sizes give orders 4, 6, 6 within ±0.15.
#[test]
fn compositions_keep_their_orders_with_a_time_dependent_force() {
    let model = Driven { x: 1.0, v: 0.0 };
    let exact = 4.0 / 3.0 * 10f64.cos() - 20f64.cos() / 3.0;
    for (method, order, steps) in [
        (Method::Yoshida4, 4.0, [100u64, 200, 400, 800]),
        (Method::Yoshida6, 6.0, [50, 100, 200, 400]),
        (Method::KahanLi6, 6.0, [25, 50, 100, 200]),
    ] {
        let points: Vec<_> = steps
            .iter()
            .map(|&n| {
                let run = model
                    .simulate()
                    .integrator(method)
                    .dt(10.0 / n as f64)
                    .steps(n)
                    .record_every(u64::MAX)
                    .run()
                    .unwrap();
                (10.0 / n as f64, (run.last().state.x - exact).abs())
            })
            .collect();
        let observed = slope(&points);
        eprintln!("{method} driven: {points:?}, order {observed:.3}");
        assert!((observed - order).abs() <= 0.15, "{method}: {observed}");
    }
}
