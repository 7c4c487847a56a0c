//! ∂f/∂p generated for `#[param]` fields (`odyn::Parameters`): against central differences of f
//! in each parameter at random states, against the hand-derived values, and the parameter
//! vector's order, round trip and length check.

use odyn::Parameters;
use odyn::nalgebra::DMatrix;
use odyn::prelude::*;

use crate::common::Rng;

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

#[test]
fn sensitivities_of_decay_match_the_closed_form() {
    use odyn::sensitivity::Sensitive;
    let decay = Decay { c: 2.0, k: 0.7 };
    let sensitive = Sensitive::with_initial_state(&decay);
    let run = sensitive
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-12, 1e-14)
        .duration(3.0)
        .save_at(&[1.0, 2.0, 3.0])
        .dense_output(true)
        .run()
        .unwrap();
    assert_eq!(run.last().state.columns(), ["k", "c(t0)"]);
    for sample in &run.samples[1..] {
        let t = sample.t;
        let e = (-0.7 * t).exp();
        let s = sample.state.sensitivities();
        // DOP853 at rtol 1e-12: errors near 1e-12 relative; 1e-9 leaves room.
        assert!((sample.state.state()[0] - 2.0 * e).abs() < 1e-9 * 2.0 * e);
        assert!(
            (s[(0, 0)] + t * 2.0 * e).abs() < 1e-9 * t * 2.0 * e,
            "t = {t}: {s}"
        );
        assert!((s[(0, 1)] - e).abs() < 1e-9 * e, "t = {t}: {s}");
    }
    assert_eq!(
        run.last().state.component_name(2),
        "dc/dc(t0)",
        "the CSV header of ∂c/∂c₀"
    );
    // Between the saved times, through DOP853's dense output (order 7 interpolant): the same
    // closed form, to 1e-8.
    for t in [0.37, 1.5, 2.71] {
        let z = run.at(t).unwrap();
        let e = (-0.7 * t).exp();
        let s = z.sensitivities();
        assert!(
            (s[(0, 0)] + t * 2.0 * e).abs() < 1e-8 * t * 2.0 * e,
            "t = {t}: {s}"
        );
        assert!((s[(0, 1)] - e).abs() < 1e-8 * e, "t = {t}: {s}");
    }
}

/// Lorenz's sensitivities at t = 1 against central differences of whole solutions, each
/// parameter ±h with h = 1e-5·p: truncation O(h²) ≈ 1e-8 relative (the third derivative of the
/// solution in p over t ≤ 1 is moderate), the solves at rtol 1e-12 add ~1e-12/h ≈ 1e-8, so 1e-7
/// relative to the column's largest entry is safe and still far below a wrong term's effect.
/// Central differences of whole solutions in each parameter: column j is
/// (y(p + hⱼeⱼ) − y(p − hⱼeⱼ))/2hⱼ with hⱼ = `relative`·pⱼ, each y the final state `solve` gives.
fn differences_of_solutions<M: Parameters + Copy>(
    model: &M,
    relative: f64,
    solve: impl Fn(&M) -> M::State,
) -> DMatrix<f64> {
    let p = model.parameters();
    let n = model.state().as_slice().len();
    let mut differences = DMatrix::zeros(n, p.len());
    for j in 0..p.len() {
        let h = relative * p[j];
        let at = |delta: f64| {
            let mut m = *model;
            let mut values = p.clone();
            values[j] += delta;
            m.set_parameters(&values).unwrap();
            solve(&m)
        };
        let (plus, minus) = (at(h), at(-h));
        for i in 0..n {
            differences[(i, j)] = (plus.as_slice()[i] - minus.as_slice()[i]) / (2.0 * h);
        }
    }
    differences
}

/// Every entry of `s` within `agreement` of `reference`, relative to the largest entry of its
/// column (the parameter's).
fn assert_columns_agree<M: Parameters>(
    s: &DMatrix<f64>,
    reference: &DMatrix<f64>,
    agreement: f64,
    what: &str,
) {
    for j in 0..s.ncols() {
        let scale = reference.column(j).amax();
        for i in 0..s.nrows() {
            assert!(
                (s[(i, j)] - reference[(i, j)]).abs() < agreement * scale,
                "{what}: ∂y{i}/∂{}: {} against {}",
                M::NAMES[j],
                s[(i, j)],
                reference[(i, j)]
            );
        }
    }
}

#[test]
fn lorenz_sensitivities_match_differences_of_solutions() {
    use odyn::sensitivity::Sensitive;
    let model = FitLorenz {
        x: 1.0,
        y: 1.0,
        z: 1.0,
        sigma: 10.0,
        rho: 28.0,
        beta: 8.0 / 3.0,
    };
    let solve = |m: &FitLorenz| {
        let run = m
            .simulate()
            .integrator(Method::Dop853)
            .tolerances(1e-12, 1e-12)
            .duration(1.0)
            .run()
            .unwrap();
        run.last().state
    };
    let run = Sensitive::new(&model)
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-12, 1e-12)
        .duration(1.0)
        .run()
        .unwrap();
    let s = run.last().state.sensitivity_matrix();
    let differences = differences_of_solutions(&model, 1e-5, solve);
    assert_columns_agree::<FitLorenz>(&s, &differences, 1e-7, "DOP853");
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

/// The augmented Jacobian (∂y′/∂y on the diagonal blocks, ∂(J·sⱼ + ∂f/∂pⱼ)/∂y below them)
/// against central differences of the augmented derivative at random states and sensitivities:
/// exact for Lorenz (f quadratic, so J linear: the model's differences are exact up to
/// rounding), and to the differences' own accuracy for the Arrhenius model (exp, powf, branches).
#[test]
fn the_augmented_jacobian_matches_differences_of_the_augmented_derivative() {
    use odyn::sensitivity::Sensitive;
    use odyn::{Jacobian, Model, State};
    fn check<M, J>(sensitive: &M, z: &M::State, t: f64, tolerance: f64)
    where
        M: Model + Jacobian<Matrix = odyn::sensitivity::AugmentedJacobian<J>>,
        J: odyn::DenseMatrix + odyn::NewtonMatrix,
    {
        let mut jacobian = sensitive.jacobian_matrix(z);
        sensitive.jacobian(t, z, &mut jacobian);
        let n = z.as_slice().len();
        // Its block solve (one factorization of the model's I − cJ) is the dense solve of the
        // whole augmented W = I − c·∂F/∂z.
        {
            use odyn::NewtonMatrix;
            let c = 0.03;
            let dense = DMatrix::from_fn(n, n, |i, k| {
                f64::from(u8::from(i == k)) - c * jacobian.entry(i, k)
            });
            let mut b: Vec<f64> = (0..n).map(|i| (1.0 + i as f64).sin()).collect();
            let expected = dense
                .lu()
                .solve(&odyn::nalgebra::DVector::from_column_slice(&b))
                .unwrap();
            let mut factors = jacobian.factors();
            jacobian.factorize(c, &mut factors).unwrap();
            jacobian.solve(&mut factors, &mut b).unwrap();
            let size = expected.amax();
            for (x, e) in b.iter().zip(expected.iter()) {
                assert!((x - e).abs() < 1e-12 * size, "{x} against {e}");
            }
        }
        let (mut plus, mut minus) = (z.clone(), z.clone());
        let scale = (0..n)
            .flat_map(|i| (0..n).map(move |k| (i, k)))
            .map(|(i, k)| jacobian.entry(i, k).abs())
            .fold(0.0, f64::max);
        for k in 0..n {
            let h = 1e-6 * (1.0 + z.as_slice()[k].abs());
            let (mut up, mut down) = (z.clone(), z.clone());
            up.as_mut_slice()[k] += h;
            down.as_mut_slice()[k] -= h;
            sensitive.derivative(t, &up, &mut plus);
            sensitive.derivative(t, &down, &mut minus);
            for i in 0..n {
                let fd = (plus.as_slice()[i] - minus.as_slice()[i]) / (2.0 * h);
                assert!(
                    (fd - jacobian.entry(i, k)).abs() < tolerance * scale,
                    "∂F{i}/∂z{k}: {} against {fd}",
                    jacobian.entry(i, k)
                );
            }
        }
    }
    let mut rng = Rng(26);
    let lorenz = FitLorenz {
        x: 1.0,
        y: 2.0,
        z: 20.0,
        sigma: 10.0,
        rho: 28.0,
        beta: 8.0 / 3.0,
    };
    let sensitive = Sensitive::with_initial_state(&lorenz);
    let mut z = sensitive.state();
    for value in z.as_mut_slice() {
        *value = rng.uniform(-5.0, 5.0);
    }
    // Central differences of a quadratic f: exact but for rounding (~1e-16·|F|/h ≈ 1e-9).
    check(&sensitive, &z, 0.0, 1e-8);
    let arrhenius = Arrhenius {
        c: 0.8,
        d: 0.1,
        a: 2.0,
        e: 300.0,
        n: 1.5,
        temperature: 350.0,
    };
    let sensitive = Sensitive::new(&arrhenius);
    let mut z = sensitive.state();
    for value in z.as_mut_slice().iter_mut().skip(2) {
        *value = rng.uniform(-1.0, 1.0);
    }
    // Two layers of differences (the test's, h ≈ 1e-6, and the Jacobian's own, δ ≈ 6e-6):
    // each O(h²) ≈ 1e-11 with moderate third derivatives, round-off ~1e-10.
    check(&sensitive, &z, 1.5, 1e-6);
}

/// Implicit Euler on the augmented system gives the exact derivative of its own discrete
/// solution: on ċ = −k·c, cₙ = c₀(1 + kh)⁻ⁿ, so ∂cₙ/∂k = −n·h·c₀(1 + kh)⁻ⁿ⁻¹ and ∂cₙ/∂c₀ =
/// (1 + kh)⁻ⁿ (differentiating the recurrence's closed form), at a stiff kh = 5.
#[test]
fn implicit_euler_sensitivities_are_the_derivatives_of_its_steps() {
    use odyn::sensitivity::Sensitive;
    let decay = Decay { c: 2.0, k: 500.0 };
    let h = 0.01;
    let run = Sensitive::with_initial_state(&decay)
        .simulate()
        .integrator(Method::ImplicitEuler)
        .dt(h)
        .steps(20)
        .run()
        .unwrap();
    for sample in &run.samples[1..] {
        let n = sample.step as i32;
        let g = 1.0 + 500.0 * h;
        let s = sample.state.sensitivities();
        let (dk, dc0) = (-f64::from(n) * h * 2.0 * g.powi(-n - 1), g.powi(-n));
        assert!((sample.state.state()[0] - 2.0 * dc0).abs() < 1e-14 * 2.0 * dc0);
        assert!(
            (s[(0, 0)] - dk).abs() < 1e-12 * dk.abs(),
            "step {n}: {s} vs {dk}"
        );
        assert!(
            (s[(0, 1)] - dc0).abs() < 1e-12 * dc0,
            "step {n}: {s} vs {dc0}"
        );
    }
}

/// Robertson's sensitivities to its three rates at t = 40 under each stiff method, against
/// central differences of whole Rodas5P solutions at rtol 1e-12, h = 1e-4·kⱼ: truncation
/// O(h²) ≈ 1e-8 relative, the solves' error over 2h ≈ 1e-12/1e-4 = 1e-8 relative; the methods
/// run at rtol 1e-10 (Rosenbrock23, third order, at 1e-9) with the sensitivities held to
/// atol/kⱼ (the fit's scaling): agreement to 1e-7 of each column's largest entry (Rosenbrock23
/// 1e-6), the reference itself being within ~5e-9 of the exact sensitivities.
#[test]
fn stiff_methods_give_robertson_sensitivities_that_match_differences_of_solutions() {
    use odyn::sensitivity::Sensitive;
    use scenes::Robertson;
    let model = Robertson::classic();
    let differences = differences_of_solutions(&model, 1e-4, |m: &Robertson| {
        m.simulate()
            .integrator(Method::Rodas5P)
            .tolerances(1e-12, 1e-20)
            .duration(40.0)
            .run()
            .unwrap()
            .last()
            .state
    });
    for (method, rtol, agreement) in [
        (Method::Rodas5P, 1e-10, 1e-7),
        (Method::Rosenbrock23, 1e-9, 1e-6),
        (Method::Bdf, 1e-10, 1e-7),
    ] {
        let sensitive = Sensitive::new(&model);
        let run = sensitive
            .simulate()
            .integrator(method)
            .with_tolerances(sensitive.tolerances(rtol, 1e-14, true))
            .duration(40.0)
            .run()
            .unwrap();
        let s = run.last().state.sensitivity_matrix();
        assert_columns_agree::<Robertson>(&s, &differences, agreement, &method.to_string());
        // The model's own work: f, J and ∂f/∂p once per augmented derivative, and J 1 + 2n = 7
        // times and ∂f/∂p 2n = 6 times per augmented Jacobian.
        let (stats, work) = (run.stats, sensitive.work());
        assert!(stats.jacobian_evaluations > 0, "{method}");
        assert_eq!(work.derivatives, stats.evaluations, "{method}");
        assert_eq!(
            work.jacobians,
            stats.evaluations + 7 * stats.jacobian_evaluations,
            "{method}"
        );
        assert_eq!(
            work.parameter_jacobians,
            stats.evaluations + 6 * stats.jacobian_evaluations,
            "{method}"
        );
    }
}

/// Sensitivities converge at the method's order: on ċ = −k·c from c₀ = 2, k = 0.7, the error of
/// ∂c/∂k and ∂c/∂c₀ at t = 1 against the closed form falls as h⁴ under RK4 and as h under
/// implicit Euler (fitted slopes of the log-log error over h = 0.1 … 0.0125).
#[test]
fn sensitivities_converge_at_the_methods_order() {
    use odyn::sensitivity::Sensitive;
    let decay = Decay { c: 2.0, k: 0.7 };
    let sensitive = Sensitive::with_initial_state(&decay);
    let (dk, dc0) = (-2.0 * (-0.7f64).exp(), (-0.7f64).exp());
    for (method, order) in [(Method::Rk4, 4.0), (Method::ImplicitEuler, 1.0)] {
        let points: Vec<(f64, f64)> = [0.1, 0.05, 0.025, 0.0125]
            .iter()
            .map(|&h| {
                let run = sensitive
                    .simulate()
                    .integrator(method)
                    .dt(h)
                    .duration(1.0)
                    .run()
                    .unwrap();
                let s = run.last().state.sensitivity_matrix();
                let error = (s[(0, 0)] - dk).abs().max((s[(0, 1)] - dc0).abs());
                (h, error)
            })
            .collect();
        let fitted = scenes::slope(&points);
        assert!(
            (fitted - order).abs() < 0.15,
            "{method}: slope {fitted}, {points:?}"
        );
    }
}

/// Leaving the sensitivities out of the error test (atol +∞ on them, CVODES's `errconS =
/// false`) sizes the steps for y alone: Robertson to t = 40 under Rodas5P takes fewer steps,
/// y is as accurate (to its tolerance), and the sensitivities, no longer controlled, still
/// agree with the controlled run's to 1e-2 of each column.
#[test]
fn sensitivities_may_be_left_out_of_the_error_test() {
    use odyn::sensitivity::Sensitive;
    use scenes::Robertson;
    let model = Robertson::classic();
    let sensitive = Sensitive::new(&model);
    let run = |included: bool| {
        sensitive
            .simulate()
            .integrator(Method::Rodas5P)
            .with_tolerances(sensitive.tolerances(1e-8, 1e-14, included))
            .duration(40.0)
            .run()
            .unwrap()
    };
    let (with, without) = (run(true), run(false));
    assert!(
        without.stats.steps < with.stats.steps,
        "{} steps without, {} with",
        without.stats.steps,
        with.stats.steps
    );
    let (a, b) = (&with.last().state, &without.last().state);
    for i in 0..3 {
        let y = a.state()[i];
        assert!(
            (y - b.state()[i]).abs() < 1e-6 * y.abs().max(1e-6),
            "y{i}: {y} against {}",
            b.state()[i]
        );
    }
    let (sa, sb) = (a.sensitivity_matrix(), b.sensitivity_matrix());
    for j in 0..3 {
        let scale = (0..3).map(|i| sa[(i, j)].abs()).fold(0.0, f64::max);
        for i in 0..3 {
            assert!(
                (sa[(i, j)] - sb[(i, j)]).abs() < 1e-2 * scale,
                "∂y{i}/∂k{j}"
            );
        }
    }
    // Every sensitivity left out and nothing else to control is refused.
    let all_out = odyn::Tolerances::per_component(1e-8, vec![f64::INFINITY; 12]);
    let error = sensitive
        .simulate()
        .integrator(Method::Rodas5P)
        .with_tolerances(all_out)
        .duration(1.0)
        .run()
        .unwrap_err();
    assert!(matches!(error, odyn::Error::InvalidInput { .. }), "{error}");
}

/// The damped pendulum's sensitivities to ω² and γ at t = 10 (the swing `fit_pendulum` fits)
/// under DOP853 at rtol 1e-11, against central differences of whole solutions at rtol 1e-13,
/// h = 1e-5·pⱼ: truncation h²/6·∂³θ/∂p³, with ∂³θ/∂(ω²)³ ~ (t/2ω)³ ≈ 4 at t = 10, is ~6e-9, the
/// solves' error over 2h ~1e-9; so 1e-7 of each column (h = 1e-4·pⱼ would leave 6e-7).
#[test]
fn pendulum_sensitivities_match_differences_of_solutions() {
    use odyn::sensitivity::Sensitive;
    use scenes::DampedPendulum;
    let model = DampedPendulum::released();
    let solve = |m: &DampedPendulum| {
        m.simulate()
            .integrator(Method::Dop853)
            .tolerances(1e-13, 1e-15)
            .duration(10.0)
            .run()
            .unwrap()
            .last()
            .state
    };
    let sensitive = Sensitive::new(&model);
    let run = sensitive
        .simulate()
        .integrator(Method::Dop853)
        .with_tolerances(sensitive.tolerances(1e-11, 1e-13, true))
        .duration(10.0)
        .run()
        .unwrap();
    let s = run.last().state.sensitivity_matrix();
    let differences = differences_of_solutions(&model, 1e-5, solve);
    assert_columns_agree::<DampedPendulum>(&s, &differences, 1e-7, "DOP853");
}
