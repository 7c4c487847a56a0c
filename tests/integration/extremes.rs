//! The extremes suite: k ∈ {1, 10³, 10⁶, 10⁹} × dt ∈ {10⁻⁶, 10⁻³, 1/60, 0.1, 1} × every method on
//! an undamped spring. Every cell either finishes finite or returns a typed divergence; nothing
//! panics; implicit Euler and the Rosenbrock methods finish every cell; and each outcome is the
//! one theory predicts.

use crate::common;

use common::Oscillator;
use odyn::Error;
use odyn::prelude::*;
use odyn::stability::stability_polynomial;

const STEPS: u64 = 1000;

/// |R(iy)| for an explicit Runge–Kutta method: the factor its step multiplies the amplitude by on
/// an undamped oscillator at ω·dt = y.
fn amplification(method: Method, y: f64) -> f64 {
    let gamma = stability_polynomial(method).expect("an explicit Runge–Kutta method");
    let (mut re, mut im) = (0.0, 0.0);
    for &g in gamma.iter().rev() {
        (re, im) = (re * 0.0 - im * y + g, re * y + im * 0.0);
    }
    re.hypot(im)
}

#[test]
fn every_cell_is_finite_or_a_typed_divergence_as_theory_predicts() {
    let mut diverged = 0;
    for k in [1.0, 1e3, 1e6, 1e9] {
        let omega: f64 = f64::sqrt(k);
        let osc = Oscillator {
            x: 1.0,
            v: 0.0,
            omega,
        };
        for dt in [1e-6, 1e-3, 1.0 / 60.0, 0.1, 1.0] {
            let h = omega * dt;
            for method in Method::ALL {
                let result = osc
                    .simulate()
                    .integrator(method)
                    .dt(dt)
                    .steps(STEPS)
                    .record_every(STEPS)
                    .run();
                let cell = format!("{method} k = {k:e} dt = {dt}");
                match result {
                    Ok(run) => {
                        let ratio = run.energy_ratio().unwrap();
                        assert!(ratio.is_finite(), "{cell}");
                        match method {
                            // Closed forms: ×(1 + h²) per step and ×1/(1 + h²) per step.
                            Method::ExplicitEuler => assert!(
                                (ratio / (1.0 + h * h).powi(STEPS as i32) - 1.0).abs() < 1e-9,
                                "{cell}: {ratio}"
                            ),
                            // L-stable (BDF at a fixed step: orders 1–2, A-stable): damped at
                            // every step size, never gaining energy.
                            Method::Rosenbrock23 | Method::Rodas5P | Method::Bdf => {
                                assert!(ratio <= 1.0 + 1e-9, "{cell}: {ratio}")
                            }
                            Method::ImplicitEuler => {
                                let expected = (1.0 + h * h).powi(-(STEPS as i32));
                                assert!(
                                    ratio <= expected * (1.0 + 1e-9) + 1e-300,
                                    "{cell}: {ratio} vs {expected}"
                                );
                            }
                            Method::Rk4 => assert!(
                                h < 2.0 * 2f64.sqrt() && ratio <= 1.0 + 1e-12,
                                "{cell}: {ratio}"
                            ),
                            // The energy is multiplied by |R(ih)|² every step, exactly.
                            Method::Tsit5 | Method::Dop853 => {
                                let expected = amplification(method, h).powi(2 * STEPS as i32);
                                assert!(
                                    (ratio / expected - 1.0).abs() < 1e-6,
                                    "{cell}: {ratio} vs {expected}"
                                );
                            }
                            // Below the first limit of the composed one-step matrix its eigenvalues
                            // lie on the unit circle. Above it the sixth-order methods have stable
                            // gaps again (Yoshida6: 2.328–2.818, scripts/stability_boundaries.py),
                            // so a finished run there is no contradiction.
                            Method::Yoshida4 | Method::Yoshida6 | Method::KahanLi6 => {
                                assert!(ratio.is_finite(), "{cell}: {ratio}")
                            }
                            _ => assert!(
                                h < 2.0 && ratio <= 2.0 / (2.0 - h) + 1e-9,
                                "{cell}: {ratio}"
                            ),
                        }
                    }
                    Err(Error::Diverged { step, .. }) => {
                        diverged += 1;
                        assert!(step <= STEPS, "{cell}");
                        match method {
                            Method::ImplicitEuler
                            | Method::Rosenbrock23
                            | Method::Rodas5P
                            | Method::Bdf => {
                                panic!("{cell}: an A-stable method diverged")
                            }
                            // Amplitude (1 + h²)^{n/2}, and |v| ≈ ω·|x|, passes the default limit
                            // 1e10 (× the initial scale 1) within n steps.
                            Method::ExplicitEuler => assert!(
                                (STEPS as f64 / 2.0) * (h * h).ln_1p() + omega.max(1.0).ln()
                                    > 10.0 * 10f64.ln() * 0.9,
                                "{cell}"
                            ),
                            Method::Rk4 => assert!(h > 2.0 * 2f64.sqrt(), "{cell}"),
                            Method::Tsit5 | Method::Dop853 => assert!(
                                STEPS as f64 * amplification(method, h).ln() + omega.max(1.0).ln()
                                    > 10.0 * 10f64.ln() * 0.9,
                                "{cell}"
                            ),
                            Method::Yoshida4 | Method::Yoshida6 | Method::KahanLi6 => {
                                assert!(h > composition_limit(method), "{cell}")
                            }
                            _ => assert!(h > 2.0, "{cell}"),
                        }
                    }
                    Err(other) => panic!("{cell}: unexpected {other}"),
                }
            }
        }
    }
    assert!(
        diverged > 30,
        "the grid should reach past every explicit limit, diverged {diverged}"
    );
}

/// The ω·h limit of a composition method, as the stability explorer predicts it for ẍ = −x
/// (measured against runs in `tests/integration/compositions.rs`).
fn composition_limit(method: Method) -> f64 {
    let unit = Oscillator {
        x: 1.0,
        v: 0.0,
        omega: 1.0,
    };
    odyn::stability::predicted_limit(&unit, 0.0, &unit.state(), method).unwrap()
}

/// An oscillator with ω = 10⁸ rad/s asked for 1 s under adaptive Rodas5P: every accepted step
/// is a fraction of 1/ω, so a budget of 2 000 steps runs out near t = 0. The error says how far
/// the rest is at the mean step so far (about 10⁹ more steps, over a thousand times the
/// budget), so it does not offer a bigger budget and names the step size as the model's time
/// scale to check. At ω = 10¹⁵¹ (k/m = 10³⁰², a probe's case) the stages overflow at every step
/// size down to the resolution of t: the run stops there at once with `StepSizeTooSmall`
/// (before, it retried the same step until its budget of 10⁶ was spent).
#[test]
fn a_time_scale_far_below_the_run_is_named_when_the_budget_runs_out() {
    let run = |omega: f64| {
        let osc = Oscillator {
            x: 1.0,
            v: 0.0,
            omega,
        };
        let control = odyn::AdaptiveOptions {
            max_steps: 2_000,
            ..odyn::AdaptiveOptions::default()
        };
        (osc.simulate().integrator(Method::Rodas5P))
            .tolerances(1e-6, 1e-9)
            .adaptive(control)
            .duration(1.0)
            .run()
            .unwrap_err()
    };
    let omega = 1e8;
    let error = run(omega);
    let Error::MaxSteps {
        mean_step, t_end, ..
    } = error
    else {
        panic!("{error}");
    };
    assert_eq!(t_end, 1.0);
    assert!(
        mean_step > 0.0 && mean_step < 10.0 / omega,
        "{mean_step:e}: {error}"
    );
    let text = error.to_string();
    assert!(text.contains("time scale"), "{text}");
    assert!(!text.contains("raise `max_steps`"), "{text}");
    let error = run(1e151);
    assert!(
        matches!(error, Error::StepSizeTooSmall { t: 0.0, .. }),
        "{error}"
    );
}
