//! One step from the same state, implicit Euler (Newton with the generated Jacobian and a stack
//! LU) beside RK4, at dt = 1e-3.

use super::*;

fn one<M: Model, I: Integrator<M>>((model, state): (M, M::State)) -> M::State {
    let mut y = state;
    let mut scratch = y.clone();
    let mut stats = Stats::default();
    let mut integrator = I::start(&model, 0.0, &y, &NewtonOptions::default(), &mut stats)
        .expect("a fixed-size model always starts");
    integrator
        .step(&model, 0.0, 1e-3, &mut y, &mut scratch, &mut stats)
        .expect("the step converges");
    y
}

#[divan::bench]
#[inline(never)]
fn spring_implicit_euler() -> SpringState {
    one::<_, ImplicitEuler<_>>(spring())
}

#[divan::bench]
#[inline(never)]
fn spring_rk4() -> SpringState {
    one::<_, Rk4<_>>(spring())
}

#[divan::bench]
#[inline(never)]
fn lorenz_implicit_euler() -> LorenzState {
    one::<_, ImplicitEuler<_>>(lorenz())
}

#[divan::bench]
#[inline(never)]
fn lorenz_rk4() -> LorenzState {
    one::<_, Rk4<_>>(lorenz())
}
