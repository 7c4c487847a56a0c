//! Parameter estimation (`odyn::fit`): exact recovery from noiseless samples, recovery within
//! the reported standard errors from noisy ones, log-parameters, and the typed errors.

use odyn::Parameters;
use odyn::fit::{Data, FitOptions, fit};
use odyn::prelude::*;

use crate::common::Rng;
use crate::parameters::{Decay, FitSpring};

/// Samples of component `component` of `model`'s solution at `times`, plus uniform noise of
/// standard deviation `sigma` (uniform on ±√3σ), weights 1/σ.
fn samples<M: Model>(model: &M, component: usize, times: &[f64], sigma: f64, seed: u64) -> Data {
    let run = model
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-12, 1e-14)
        .duration(*times.last().unwrap())
        .save_at(times)
        .run()
        .unwrap();
    let mut rng = Rng(seed);
    let half_width = 3f64.sqrt() * sigma;
    let values = times
        .iter()
        .map(|&t| {
            let exact = run.sample_at(t).unwrap().state.as_slice()[component];
            exact
                + if sigma > 0.0 {
                    rng.uniform(-half_width, half_width)
                } else {
                    0.0
                }
        })
        .collect();
    Data {
        component,
        times: times.to_vec(),
        values,
        weights: if sigma > 0.0 {
            vec![1.0 / sigma; times.len()]
        } else {
            Vec::new()
        },
    }
}

fn times(count: usize, end: f64) -> Vec<f64> {
    (1..=count).map(|k| end * k as f64 / count as f64).collect()
}

#[test]
fn noiseless_decay_recovers_its_rate() {
    let truth = Decay { c: 2.0, k: 0.7 };
    let data = samples(&truth, 0, &times(20, 4.0), 0.0, 1);
    for log_parameters in [false, true] {
        let guess = Decay { c: 2.0, k: 0.2 };
        let options = FitOptions {
            log_parameters,
            ..FitOptions::default()
        };
        let found = fit(&guess, std::slice::from_ref(&data), &options).unwrap();
        // The data come from solves at rtol 1e-12, the fit's at 1e-10: agreement to ~1e-9.
        assert!(
            (found.parameters[0] - 0.7).abs() < 1e-8,
            "log {log_parameters}: {found:?}"
        );
        assert!(found.cost < 1e-16 && found.initial_cost > 1e-2, "{found:?}");
    }
}

#[test]
fn noisy_spring_recovers_stiffness_and_damping_within_their_standard_errors() {
    let truth = FitSpring {
        x: 1.0,
        v: 0.0,
        k: 50.0,
        b: 0.5,
        m: 1.0,
    };
    let data = samples(&truth, 0, &times(200, 4.0), 0.01, 42);
    let guess = FitSpring {
        k: 45.0,
        b: 1.0,
        ..truth
    };
    let found = fit(&guess, &[data], &FitOptions::default()).unwrap();
    assert_eq!(FitSpring::NAMES, ["k", "b"]);
    for (j, truth) in [50.0, 0.5].into_iter().enumerate() {
        let (value, error) = (found.parameters[j], found.standard_errors[j]);
        // Four standard errors: a true value outside them has probability < 1e-4 under the
        // Gauss–Newton model; the errors themselves must be small but non-zero.
        assert!((value - truth).abs() < 4.0 * error, "{j}: {found:?}");
        assert!(error > 0.0 && error < 0.05 * truth, "{j}: {found:?}");
    }
    // Weighted residuals of noise with σ = 1 each: 2·cost ≈ m − n = 198 (χ² within ±5 of its
    // standard deviation √(2·198) ≈ 20, for uniform noise smaller still).
    assert!((2.0 * found.cost - 198.0).abs() < 100.0, "{found:?}");
}

#[test]
fn bad_data_and_exhausted_iterations_are_typed_errors() {
    let model = Decay { c: 2.0, k: 0.7 };
    let mut data = samples(&model, 0, &times(5, 1.0), 0.0, 1);
    data.values.pop();
    let error = fit(&model, &[data], &FitOptions::default()).unwrap_err();
    assert!(matches!(error, odyn::Error::InvalidInput { .. }), "{error}");

    let data = samples(&model, 0, &times(5, 1.0), 0.0, 1);
    let backwards = Data {
        times: data.times.iter().rev().copied().collect(),
        ..data.clone()
    };
    let error = fit(&model, &[backwards], &FitOptions::default()).unwrap_err();
    assert!(error.to_string().contains("increasing"), "{error}");

    for (values, weights) in [
        (vec![f64::NAN], vec![]),
        (vec![f64::INFINITY], vec![]),
        (vec![1.0], vec![f64::NAN]),
        (vec![1.0], vec![-1.0]),
    ] {
        let mut bad = data.clone();
        bad.values[2] = values[0];
        if let Some(&w) = weights.first() {
            bad.weights = vec![1.0; bad.times.len()];
            bad.weights[2] = w;
        }
        let error = fit(&model, &[bad], &FitOptions::default()).unwrap_err();
        assert!(
            matches!(error, odyn::Error::InvalidInput { .. }) && error.to_string().contains(" 2 "),
            "{error}"
        );
    }
    let error = fit(&model, &[], &FitOptions::default()).unwrap_err();
    assert!(error.to_string().contains("0 samples"), "{error}");

    let far = Decay { c: 2.0, k: 5.0 };
    let options = FitOptions {
        max_iterations: 1,
        ..FitOptions::default()
    };
    let error = fit(&far, std::slice::from_ref(&data), &options).unwrap_err();
    assert!(
        matches!(error, odyn::Error::FitDidNotConverge { iterations: 1, .. }),
        "{error}"
    );

    let negative = Decay { c: 2.0, k: -1.0 };
    let options = FitOptions {
        log_parameters: true,
        ..FitOptions::default()
    };
    let error = fit(&negative, &[data], &options).unwrap_err();
    assert!(error.to_string().contains("positive"), "{error}");
}

/// Position and velocity measured together: both data sets' residuals in one fit.
#[test]
fn two_measured_components_fit_together() {
    let truth = FitSpring {
        x: 1.0,
        v: 0.0,
        k: 50.0,
        b: 0.5,
        m: 1.0,
    };
    let positions = samples(&truth, 0, &times(50, 2.0), 0.0, 1);
    // Velocities at other times than the positions: the solve saves at the merged times.
    let velocity_times: Vec<f64> = times(40, 2.0).iter().map(|t| t - 0.01).collect();
    let velocities = samples(&truth, 1, &velocity_times, 0.0, 1);
    let guess = FitSpring {
        k: 40.0,
        b: 0.2,
        ..truth
    };
    let found = fit(&guess, &[positions, velocities], &FitOptions::default()).unwrap();
    // Noiseless data from solves at rtol 1e-12 against the fit's 1e-10: agreement to ~1e-8.
    assert!((found.parameters[0] - 50.0).abs() < 1e-6, "{found:?}");
    assert!((found.parameters[1] - 0.5).abs() < 1e-7, "{found:?}");
}

/// A stiff fit: Robertson's three rates, spread over nine orders of magnitude, from noiseless
/// concentrations at 21 times from 10⁻⁴ to 10⁴, in log-parameters, solved by Rodas5P with its
/// sensitivities. The truth is a zero-residual minimum, so the fit lands on it to the solves'
/// accuracy: 1e-5 relative (rtol 1e-9).
#[test]
fn robertson_rates_are_recovered_by_a_stiff_fit() {
    use scenes::Robertson;
    let truth = Robertson::classic();
    let times: Vec<f64> = (0..=20)
        .map(|k| 10f64.powf(-4.0 + 0.4 * f64::from(k)))
        .collect();
    let run = truth
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-12, 1e-20)
        .duration(1e4)
        .save_at(&times)
        .run()
        .unwrap();
    let data: Vec<Data> = (0..3)
        .map(|species| {
            let values: Vec<f64> = times
                .iter()
                .map(|&t| run.sample_at(t).unwrap().state.as_slice()[species])
                .collect();
            Data {
                component: species,
                times: times.clone(),
                weights: values.iter().map(|v| 1.0 / v.abs()).collect(),
                values,
            }
        })
        .collect();
    let guess = Robertson {
        k1: 0.02,
        k2: 3e4,
        k3: 1e7,
        ..truth
    };
    let options = FitOptions {
        integrator: Method::Rodas5P,
        rtol: 1e-9,
        atol: 1e-18,
        log_parameters: true,
        ..FitOptions::default()
    };
    let found = fit(&guess, &data, &options).unwrap();
    for (j, (p, t)) in found.parameters.iter().zip(truth.parameters()).enumerate() {
        assert!((p / t - 1.0).abs() < 1e-5, "k{}: {p} against {t}", j + 1);
    }
}

/// The reported standard errors mean what they say: over 40 seeded noise draws of the spring
/// fit, the truth lies within two standard errors of the fitted value in ≥ 34 of 40 for each
/// parameter (95 % expected: 38; ≥ 34 fails with probability < 3 % if the errors are right,
/// binomial), and within one in 20 to 35 of 40 (68 %: 27 ± 3).
#[test]
fn standard_errors_cover_the_truth_over_repeated_noise() {
    let truth = FitSpring {
        x: 1.0,
        v: 0.0,
        k: 50.0,
        b: 0.5,
        m: 1.0,
    };
    let guess = FitSpring {
        k: 48.0,
        b: 0.7,
        ..truth
    };
    let mut within = [[0; 2]; 2];
    for seed in 1..=40 {
        let data = samples(&truth, 0, &times(100, 4.0), 0.02, 1000 + seed);
        let found = fit(&guess, &[data], &FitOptions::default()).unwrap();
        for (j, t) in [50.0, 0.5].into_iter().enumerate() {
            let z = (found.parameters[j] - t).abs() / found.standard_errors[j];
            within[j][0] += usize::from(z < 1.0);
            within[j][1] += usize::from(z < 2.0);
        }
    }
    for (j, [one, two]) in within.into_iter().enumerate() {
        assert!(two >= 34, "parameter {j}: {two} of 40 within 2σ");
        assert!(
            (20..=35).contains(&one),
            "parameter {j}: {one} of 40 within 1σ"
        );
    }
}

/// ċ = −k·(c − level): relaxation to a level, at rate k.
#[system]
#[derive(Clone, Copy, Debug)]
struct Relax {
    #[state]
    c: f64,
    #[param]
    k: f64,
    #[param]
    level: f64,
}

#[system]
impl Relax {
    fn derivative(&self) -> RelaxState {
        RelaxState {
            c: -self.k * (self.c - self.level),
        }
    }
}

/// Ten samples between 1e-10 and 1e-9 of a relaxation at k = 1e9: the fit once read all ten
/// from the one sample within 1e-9 of them (k = 9.8e8, level 1.04 instead of 1e9 and 0.5);
/// it reads each sample at its own time now. The data are the closed form
/// c = level + (c₀ − level)·e^{−kt}.
#[test]
fn closely_spaced_samples_are_read_at_their_own_times() {
    let (k, level) = (1e9, 0.5);
    let times: Vec<f64> = (1..=10).map(|i| i as f64 * 1e-10).collect();
    let values = times
        .iter()
        .map(|t| level + (1.0 - level) * (-k * t).exp())
        .collect();
    let data = Data {
        component: 0,
        times,
        values,
        weights: Vec::new(),
    };
    let guess = Relax {
        c: 1.0,
        k: 0.7e9,
        level: 0.6,
    };
    let options = FitOptions {
        log_parameters: true,
        ..FitOptions::default()
    };
    let found = fit(&guess, &[data], &options).unwrap();
    assert!(
        (found.parameters[0] / k - 1.0).abs() < 1e-6 && (found.parameters[1] - level).abs() < 1e-6,
        "{found:?}"
    );
}

/// What once returned Ok without fitting: a value of 1e300 (cost ∞ at the guess, parameters
/// unchanged), all weights zero (cost 0 after one iteration, NaN standard errors); and options
/// that were not checked (a NaN step tolerance ran out the iterations, a fixed-step method was
/// told to take a `dt` it cannot be given).
#[test]
fn fits_that_cannot_fit_are_typed_errors() {
    let truth = Decay { c: 2.0, k: 0.7 };
    let data = samples(&truth, 0, &times(10, 2.0), 0.0, 1);
    let options = FitOptions::default();
    let mut huge = data.clone();
    huge.values[3] = 1e300;
    match fit(&truth, &[huge], &options) {
        Err(Error::FitStart {
            parameters,
            problem,
        }) => {
            assert!(
                parameters.contains("k = 7e-1") && problem.contains("sample 3"),
                "{problem}"
            );
        }
        other => panic!("expected FitStart, got {other:?}"),
    }
    let zero = Data {
        weights: vec![0.0; 10],
        ..data.clone()
    };
    let error = fit(&truth, &[zero], &options).unwrap_err();
    assert!(
        matches!(&error, Error::InvalidInput { reason, .. } if reason.contains("non-zero weight")),
        "{error}"
    );
    let bad_options = [
        FitOptions {
            step_tolerance: f64::NAN,
            ..FitOptions::default()
        },
        FitOptions {
            integrator: Method::Rk4,
            ..FitOptions::default()
        },
        FitOptions {
            rtol: -1.0,
            ..FitOptions::default()
        },
        FitOptions {
            max_iterations: 0,
            ..FitOptions::default()
        },
    ];
    for (options, field) in bad_options.iter().zip([
        "FitOptions::step_tolerance",
        "FitOptions::method",
        "FitOptions::rtol",
        "FitOptions::max_iterations",
    ]) {
        match fit(&truth, std::slice::from_ref(&data), options) {
            Err(Error::InvalidInput { field: f, .. }) => assert_eq!(f, field),
            other => panic!("{field}: expected InvalidInput, got {other:?}"),
        }
    }
    // A guess whose solve blows up names the parameters, not the sensitivity component, and
    // does not advise a dt.
    let blowing = Decay { c: 2.0, k: -800.0 };
    match fit(&blowing, std::slice::from_ref(&data), &options) {
        Err(error @ Error::FitStart { .. }) => {
            let text = error.to_string();
            assert!(text.contains("k = -8e2") && !text.contains("dt"), "{text}");
        }
        other => panic!("expected FitStart, got {other:?}"),
    }
}

/// ẍ = −k·x: an undamped oscillator whose one parameter sets its frequency.
#[system]
#[derive(Clone, Copy, Debug)]
struct Tone {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    #[param]
    k: f64,
}

#[system]
impl Tone {
    fn acceleration(&self) -> f64 {
        -self.k * self.x
    }
}

/// The reduced χ² of a fit and its consistency with weights 1/σ: from a guess near the truth
/// the oscillator's frequency is found (χ²/ν near 1, consistent); from one far from it, a local
/// minimum of the oscillating residuals (χ²/ν in the thousands, inconsistent). ν = 100 − 1.
#[test]
fn a_local_minimum_is_reported_inconsistent_with_its_noise() {
    let truth = Tone {
        x: 1.0,
        v: 0.0,
        k: 50.0,
    };
    let sigma = 0.01;
    let data = samples(&truth, 0, &times(100, 10.0), sigma, 3);
    let near = fit(
        &Tone { k: 48.0, ..truth },
        std::slice::from_ref(&data),
        &FitOptions::default(),
    )
    .unwrap();
    assert_eq!(near.degrees_of_freedom, 99);
    assert!(
        near.consistent() && (near.parameters[0] - 50.0).abs() < 0.1,
        "{near:?}"
    );
    // From k = 40 the search stops at k ≈ 39.6, a minimum of the residuals' oscillation in k.
    let far = fit(
        &Tone { k: 40.0, ..truth },
        std::slice::from_ref(&data),
        &FitOptions::default(),
    )
    .unwrap();
    assert!((far.parameters[0] - 50.0).abs() > 5.0, "{far:?}");
    assert!(
        !far.consistent() && far.reduced_chi_squared > 100.0,
        "{far:?}"
    );
}
