//! Lorenz's system: explicit Euler and RK4, generated and through the runner, against the same
//! steps by hand.

use super::*;

fn f(l: &Lorenz, [x, y, z]: [f64; 3]) -> [f64; 3] {
    [l.sigma * (y - x), x * (l.rho - z) - y, x * y - l.beta * z]
}

fn axpy(y: [f64; 3], a: f64, k: [f64; 3]) -> [f64; 3] {
    [y[0] + a * k[0], y[1] + a * k[1], y[2] + a * k[2]]
}

#[divan::bench]
fn explicit_euler_generated() -> LorenzState {
    generated::<_, ExplicitEuler<_>>(&lorenz())
}
#[divan::bench]
fn explicit_euler_runner() -> LorenzState {
    runner(&lorenz(), Method::ExplicitEuler)
}
#[divan::bench]
fn explicit_euler_hand() -> [f64; 3] {
    let l = lorenz();
    let mut y = [l.x, l.y, l.z];
    for _ in 0..STEPS {
        y = axpy(y, DT, f(&l, y));
    }
    y
}

#[divan::bench]
fn rk4_generated() -> LorenzState {
    generated::<_, Rk4<_>>(&lorenz())
}
#[divan::bench]
fn rk4_runner() -> LorenzState {
    runner(&lorenz(), Method::Rk4)
}
#[divan::bench]
fn rk4_hand() -> [f64; 3] {
    let l = lorenz();
    let mut y = [l.x, l.y, l.z];
    for _ in 0..STEPS {
        let k1 = f(&l, y);
        let k2 = f(&l, axpy(y, 0.5 * DT, k1));
        let k3 = f(&l, axpy(y, 0.5 * DT, k2));
        let k4 = f(&l, axpy(y, DT, k3));
        for i in 0..3 {
            y[i] += DT / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    y
}
