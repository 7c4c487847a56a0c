//! Differential–algebraic models beyond the references: a `Stepper`, forward sensitivities,
//! and a model above 32 components.

use odyn::Stepper;
use odyn::prelude::*;
use odyn::sensitivity::Sensitive;
use scenes::{CartesianPendulum, PENDULUM_1, PENDULUM_Y0, RobertsonDae};

use super::relative;

/// A `Stepper` with Rodas5P repairs the start and steps the DAE at a fixed step: 100 steps of
/// 0.01 reach the exact state at t = 1 within 1e-6.
#[test]
fn a_stepper_steps_a_dae() {
    let pendulum = CartesianPendulum::released(0.0, 0.0);
    let mut stepper =
        Stepper::<_, odyn::integrators::Rodas5P<_>>::new(&pendulum, pendulum.state(), 0.0, 0.01)
            .unwrap();
    assert!((stepper.state().lambda - PENDULUM_Y0[4]).abs() < 1e-12);
    for _ in 0..100 {
        stepper.step().unwrap();
    }
    let error = relative(stepper.state().as_slice(), &PENDULUM_1);
    assert!(error < 1e-6, "{error}");
}

/// Forward sensitivities of a DAE (M·sⱼ′ = J·sⱼ + ∂f/∂pⱼ, the algebraic ones made consistent):
/// Robertson-DAE's ∂y/∂(k₁, k₂, k₃) at t = 40 are the ODE form's (the two have one solution, so
/// one derivative with respect to the rates), within 1e-6 of each column's largest entry under
/// Rodas5P and BDF at rtol 1e-10 (measured 4e-14 and 5e-10: at equal tolerances Rodas5P takes
/// the same steps on both forms, whose stages keep the linear invariant); the algebraic row
/// keeps s₁ + s₂ + s₃ = 0.
#[test]
fn sensitivities_of_a_dae_match_the_ode_form() {
    let (ode_model, dae_model) = (scenes::Robertson::classic(), RobertsonDae::classic());
    let ode = Sensitive::new(&ode_model);
    let reference = ode
        .simulate()
        .integrator(Method::Rodas5P)
        .with_tolerances(ode.tolerances(1e-11, 1e-16, true))
        .duration(40.0)
        .record_every(u64::MAX)
        .run()
        .unwrap()
        .last()
        .state
        .sensitivity_matrix();
    let dae = Sensitive::new(&dae_model);
    for method in [Method::Rodas5P, Method::Bdf] {
        let run = dae
            .simulate()
            .integrator(method)
            .with_tolerances(dae.tolerances(1e-10, 1e-16, true))
            .duration(40.0)
            .record_every(u64::MAX)
            .run()
            .unwrap();
        let s = run.last().state.sensitivity_matrix();
        for c in 0..3 {
            let scale = reference.column(c).amax();
            let error = (s.column(c) - reference.column(c)).amax() / scale;
            eprintln!("{method}, ∂y/∂k{}: relative error {error:.1e}", c + 1);
            assert!(error < 1e-6, "{method}, column {c}: {error}");
            assert!(
                s.column(c).sum().abs() < 1e-12 * scale,
                "{method}: {}",
                s.column(c)
            );
        }
    }
}

/// A DAE above 32 components takes faer's dense LU (`FaerDense`): 20 decays xᵢ′ = −kᵢ·zᵢ with
/// the algebraic zᵢ = xᵢ, started from z = 0 (inconsistent: repaired to z = x), reach
/// xᵢ(1) = e^(−kᵢ), kᵢ = 0.1·(i + 1), within 1e-8 under Rodas5P and BDF at rtol 1e-10.
#[test]
fn a_big_dae_runs_on_the_heap_matrix() {
    #[system]
    #[derive(Clone, Copy, Debug)]
    struct Decays {
        #[state]
        x: [f64; 20],
        #[algebraic]
        z: [f64; 20],
    }
    #[system]
    impl Decays {
        fn derivative(&self) -> DecaysState {
            let mut x = [0.0; 20];
            let mut z = [0.0; 20];
            for i in 0..20 {
                x[i] = -0.1 * (i + 1) as f64 * self.z[i];
                z[i] = self.z[i] - self.x[i];
            }
            DecaysState { x, z }
        }
    }
    let model = Decays {
        x: [1.0; 20],
        z: [0.0; 20],
    };
    for method in [Method::Rodas5P, Method::Bdf] {
        let run = model
            .simulate()
            .integrator(method)
            .tolerances(1e-10, 1e-12)
            .duration(1.0)
            .run()
            .unwrap();
        assert_eq!(run.first().state.z, [1.0; 20]);
        let end = run.last().state;
        for i in 0..20 {
            let exact = (-0.1 * (i + 1) as f64).exp();
            assert!(
                (end.x[i] - exact).abs() < 1e-8,
                "{method}: x[{i}] = {}",
                end.x[i]
            );
            assert!((end.z[i] - end.x[i]).abs() < 1e-12, "{method}: z[{i}]");
        }
    }
}
