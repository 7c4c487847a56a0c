//! Forward sensitivities against closed forms: exponential decay, the derivatives of implicit
//! Euler's own steps, convergence at the method's order, and leaving them out of the error test.

use odyn::prelude::*;

use super::Decay;

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
