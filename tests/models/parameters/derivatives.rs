//! ∂f/∂p against hand-derived values and central differences, and the parameter vector's
//! order, round trip and length check.

use odyn::Parameters;
use odyn::nalgebra::DMatrix;
use odyn::prelude::*;

use super::{Arrhenius, ArrheniusState, FitLorenz, FitLorenzParameters, FitLorenzState, FitSpring};
use crate::common::Rng;

/// ∂f/∂p by central differences in each parameter: h = 1e-6·(1 + |pⱼ|) leaves truncation
/// (∝ h²) and round-off (∝ ε/h) near 1e-9 relative, so 1e-6 relative to the column's largest
/// entry is strict but safe (as for ∂f/∂y in `common::check`).
fn check<M: Parameters + Clone>(model: &M, t: f64, y: &M::State) {
    let mut exact = DMatrix::zeros(0, 0);
    model.parameter_jacobian(t, y, &mut exact);
    let p = model.parameters();
    let n = y.as_slice().len();
    assert_eq!(exact.shape(), (n, p.len()));
    for j in 0..p.len() {
        let h = 1e-6 * (1.0 + p[j].abs());
        let at = |delta: f64| {
            let mut shifted = model.clone();
            let mut values = p.clone();
            values[j] += delta;
            shifted.set_parameters(&values).unwrap();
            let mut f = y.clone();
            shifted.derivative(t, y, &mut f);
            f
        };
        let (plus, minus) = (at(h), at(-h));
        let scale = (0..n).map(|i| exact[(i, j)].abs()).fold(1e-12, f64::max);
        for i in 0..n {
            let fd = (plus.as_slice()[i] - minus.as_slice()[i]) / (2.0 * h);
            assert!(
                (fd - exact[(i, j)]).abs() <= 1e-6 * scale,
                "∂f{i}/∂{}: exact {} against central difference {fd}",
                M::NAMES[j],
                exact[(i, j)]
            );
        }
    }
}

#[test]
fn spring_parameters_match_the_hand_derived_values() {
    let spring = FitSpring {
        x: 0.3,
        v: -1.2,
        k: 50.0,
        b: 0.5,
        m: 2.0,
    };
    let mut dfdp = DMatrix::zeros(0, 0);
    spring.parameter_jacobian(0.0, &spring.state(), &mut dfdp);
    // Rows x, v (the layout); ẋ = v reads no parameter.
    assert_eq!(dfdp, DMatrix::from_row_slice(2, 2, &[0.0, 0.0, -0.15, 0.6]));
    assert_eq!(FitSpring::NAMES, ["k", "b"]);
    check(&spring, 0.0, &spring.state());
}

/// The scenes' models with parameters — Robertson's rates, the damped pendulum's ω² and γ —
/// against central differences at random states.
#[test]
fn scene_parameters_match_central_differences() {
    let mut rng = Rng(11);
    let robertson = scenes::Robertson::classic();
    let pendulum = scenes::DampedPendulum::released();
    for _ in 0..20 {
        let y = scenes::RobertsonState {
            a: rng.uniform(0.0, 1.0),
            b: rng.uniform(0.0, 4e-5),
            c: rng.uniform(0.0, 1.0),
        };
        check(&robertson, 0.0, &y);
        let y = scenes::DampedPendulumState {
            theta: rng.uniform(-3.0, 3.0),
            omega: rng.uniform(-5.0, 5.0),
        };
        check(&pendulum, 0.0, &y);
    }
}

#[test]
fn lorenz_parameters_match_central_differences() {
    let mut rng = Rng(7);
    let model = FitLorenz {
        x: 1.0,
        y: 1.0,
        z: 1.0,
        sigma: 10.0,
        rho: 28.0,
        beta: 8.0 / 3.0,
    };
    for _ in 0..20 {
        let y = FitLorenzState {
            x: rng.uniform(-20.0, 20.0),
            y: rng.uniform(-20.0, 20.0),
            z: rng.uniform(0.0, 50.0),
        };
        check(&model, 0.0, &y);
    }
    // ∂ẏ/∂ρ = x exactly.
    let mut dfdp = DMatrix::zeros(3, 3);
    model.parameter_jacobian(0.0, &model.state(), &mut dfdp);
    assert_eq!(dfdp[(1, 1)], 1.0);
}

#[test]
fn functions_branches_and_locals_of_parameters_are_differentiated() {
    let mut rng = Rng(11);
    for n in [0.7, 1.6] {
        let model = Arrhenius {
            c: 1.0,
            d: 0.0,
            a: 3.0,
            e: 2.0,
            n,
            temperature: 1.5,
        };
        for t in [0.5, 2.0] {
            for _ in 0..10 {
                let y = ArrheniusState {
                    c: rng.uniform(0.1, 2.0),
                    d: rng.uniform(0.0, 1.0),
                };
                check(&model, t, &y);
            }
        }
    }
}

#[test]
fn parameters_round_trip_and_a_wrong_length_is_an_error() {
    let mut model = FitLorenz {
        x: 1.0,
        y: 2.0,
        z: 3.0,
        sigma: 10.0,
        rho: 28.0,
        beta: 8.0 / 3.0,
    };
    assert_eq!(model.parameters(), [10.0, 28.0, 8.0 / 3.0]);
    model.set_parameters(&[1.0, 2.0, 3.0]).unwrap();
    assert_eq!((model.sigma, model.rho, model.beta), (1.0, 2.0, 3.0));
    assert_eq!((model.x, model.y, model.z), (1.0, 2.0, 3.0));
    let error = model.set_parameters(&[1.0]).unwrap_err();
    assert!(matches!(error, odyn::Error::InvalidInput { .. }), "{error}");
    assert!(error.to_string().contains("sigma, rho, beta"), "{error}");
    // The typed parameter struct generated beside the state type.
    let values = model.parameter_values();
    assert_eq!(
        values,
        FitLorenzParameters {
            sigma: 1.0,
            rho: 2.0,
            beta: 3.0
        }
    );
    model.set_parameter_values(FitLorenzParameters {
        rho: 28.0,
        ..values
    });
    assert_eq!(model.parameters(), [1.0, 28.0, 3.0]);
    assert_eq!((model.x, model.y, model.z), (1.0, 2.0, 3.0));
}

/// A first-order model of one scalar state may return its derivative as an `f64`.
#[system]
#[derive(Clone, Copy, Debug)]
pub struct ScalarDecay {
    #[state]
    pub c: f64,
    pub k: f64,
}

#[system]
impl ScalarDecay {
    fn derivative(&self) -> f64 {
        -self.k * self.c
    }
}

#[test]
fn a_one_component_model_may_return_f64() {
    let model = ScalarDecay { c: 2.0, k: 0.7 };
    let run = model
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-10, 1e-12)
        .duration(1.0)
        .run()
        .unwrap();
    // c(1) = 2·e^{−0.7}; Rodas5P at rtol 1e-10.
    assert!((run.last().state.c - 2.0 * (-0.7f64).exp()).abs() < 1e-8);
}
