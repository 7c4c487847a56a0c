//! A model of two megabyte arrays, simulated from a thread with the main thread's stack: the
//! runtime's room on the stack for big states. In the optimised binary: unoptimised, the
//! model's own `derivative` (two megabyte locals and the state it returns) needs more than
//! 8 MiB by itself.
#![allow(missing_docs)]

use odyn::prelude::*;

/// ẏᵢ = −λᵢ·yᵢ on two megabyte arrays (2·65 536 components, Gray–Scott on 256² in size), written
/// with loops, so without a Jacobian. Runs on such states used to overflow the stack and abort.
#[system(integrator = Rk4, dt = 0.1, jacobian = false)]
pub struct Decay {
    #[state]
    pub u: [f64; 65536],
    #[state]
    pub v: [f64; 65536],
}

#[system]
impl Decay {
    fn derivative(&self) -> DecayState {
        let mut du = [0.0; 65536];
        let mut dv = [0.0; 65536];
        for i in 0..65536 {
            let rate = 1.0 + (i % 7) as f64 * 0.1;
            du[i] = -rate * self.u[i];
            dv[i] = -2.0 * rate * self.v[i];
        }
        DecayState { u: du, v: dv }
    }
}

/// Simulation (fixed and adaptive) and Stepper on a 1 MiB state, from a thread with the main
/// thread's 8 MiB stack: each finishes with the right numbers. RK4 on ẏ = λy is the recurrence
/// yₙ = R(λ·dt)ⁿ·y₀ with R(z) = 1 + z + z²/2 + z³/6 + z⁴/24 (its stability polynomial), exact to
/// round-off; DOP853 at rtol 1e-10 is checked against e^(λt) to 1e-7.
#[test]
fn megabyte_states_do_not_overflow_the_stack() {
    let rk4 = |z: f64| 1.0 + z + z * z / 2.0 + z.powi(3) / 6.0 + z.powi(4) / 24.0;
    let check = |state: &DecayState, expected: &dyn Fn(f64) -> f64, tolerance: f64| {
        for i in (0..65536).step_by(997) {
            let rate = 1.0 + (i % 7) as f64 * 0.1;
            let (u, v) = (expected(-rate), expected(-2.0 * rate));
            assert!(
                (state.u[i] - u).abs() <= tolerance * u,
                "u[{i}] = {} vs {u}",
                state.u[i]
            );
            assert!(
                (state.v[i] - v).abs() <= tolerance * v,
                "v[{i}] = {} vs {v}",
                state.v[i]
            );
        }
    };
    let recurrence = move |lambda: f64| rk4(lambda * 0.1).powi(10);
    std::thread::Builder::new()
        .stack_size(8 << 20)
        .spawn(move || {
            let model = decay();
            let run = model
                .simulate()
                .steps(10)
                .run_with::<odyn::method::Rk4>()
                .unwrap();
            check(&run.samples.last().unwrap().state, &recurrence, 1e-13);
            let run = model
                .simulate()
                .tolerances(1e-10, 1e-12)
                .duration(1.0)
                .run_with::<odyn::method::Dop853>()
                .unwrap();
            check(&run.samples.last().unwrap().state, &|l: f64| l.exp(), 1e-7);
            check(&stepped(&model), &recurrence, 1e-13);
        })
        .unwrap()
        .join()
        .unwrap();
}

// Each in a function of its own, so the test's frames hold one megabyte value at a time, as a
// user's `main` would.
fn decay() -> Box<Decay> {
    Box::new(Decay {
        u: [1.0; 65536],
        v: [1.0; 65536],
    })
}

fn stepped(model: &Decay) -> Box<DecayState> {
    let mut stepper =
        odyn::Stepper::<_, odyn::integrators::Rk4<_>>::new(model, model.state(), 0.0, 0.1).unwrap();
    for _ in 0..10 {
        stepper.step().unwrap();
    }
    Box::new(*stepper.state())
}
