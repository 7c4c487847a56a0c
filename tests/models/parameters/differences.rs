//! Forward sensitivities against central differences of whole solutions (Lorenz, Robertson under
//! each stiff method, the damped pendulum), and the augmented Jacobian against differences of the
//! augmented derivative.

use odyn::Parameters;
use odyn::nalgebra::DMatrix;
use odyn::prelude::*;

use super::{Arrhenius, FitLorenz};
use crate::common::Rng;

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

/// Lorenz's sensitivities at t = 1 against central differences of whole solutions, each
/// parameter ±h with h = 1e-5·p: truncation O(h²) ≈ 1e-8 relative (the third derivative of the
/// solution in p over t ≤ 1 is moderate), the solves at rtol 1e-12 add ~1e-12/h ≈ 1e-8, so 1e-7
/// relative to the column's largest entry is safe and still far below a wrong term's effect.
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
        // One run of this `Sensitive`: its stats carry all of its work.
        assert_eq!(stats.sensitivity, work, "{method}");
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
