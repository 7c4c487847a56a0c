//! A damped spring: explicit Euler, RK4 and the symplectic methods, generated and through the
//! runner, against the same steps by hand.

use super::*;

fn accel(s: &Spring, x: f64, v: f64) -> f64 {
    (-s.k * x - s.b * v) / s.m
}

#[divan::bench]
fn explicit_euler_generated() -> SpringState {
    generated::<_, ExplicitEuler<_>>(&spring())
}
#[divan::bench]
fn explicit_euler_runner() -> SpringState {
    runner(&spring(), Method::ExplicitEuler)
}
#[divan::bench]
fn explicit_euler_hand() -> (f64, f64) {
    let s = spring();
    let (mut x, mut v) = (s.x, s.v);
    for _ in 0..STEPS {
        let a = accel(&s, x, v);
        x += DT * v;
        v += DT * a;
    }
    (x, v)
}

#[divan::bench]
fn symplectic_euler_generated() -> SpringState {
    generated::<_, SymplecticEuler<_>>(&spring())
}
#[divan::bench]
fn symplectic_euler_runner() -> SpringState {
    runner(&spring(), Method::SymplecticEuler)
}
#[divan::bench]
fn symplectic_euler_hand() -> (f64, f64) {
    let s = spring();
    let (mut x, mut v) = (s.x, s.v);
    for _ in 0..STEPS {
        v += DT * accel(&s, x, v);
        x += DT * v;
    }
    (x, v)
}

#[divan::bench]
fn position_verlet_generated() -> UndampedSpringState {
    let u = black_box(UndampedSpring {
        x: 1.0,
        v: 0.0,
        k: 50.0,
        m: 1.0,
    });
    generated::<_, PositionVerlet<_>>(&u)
}
#[divan::bench]
fn position_verlet_hand() -> (f64, f64) {
    let u = black_box(UndampedSpring {
        x: 1.0,
        v: 0.0,
        k: 50.0,
        m: 1.0,
    });
    let acc = |x: f64| -u.k / u.m * x;
    let mut a = acc(u.x);
    let (mut prev, mut x, mut v) = (u.x, u.x + DT * u.v + 0.5 * DT * DT * a, 0.0);
    a = acc(x);
    for _ in 1..STEPS {
        let next = 2.0 * x - prev + DT * DT * a;
        a = acc(next);
        v = (next - x) / DT + 0.5 * DT * a;
        prev = x;
        x = next;
    }
    (x, v)
}

#[divan::bench]
fn velocity_verlet_generated() -> SpringState {
    generated::<_, VelocityVerlet<_>>(&spring())
}
#[divan::bench]
fn velocity_verlet_runner() -> SpringState {
    runner(&spring(), Method::VelocityVerlet)
}
#[divan::bench]
fn velocity_verlet_hand() -> (f64, f64) {
    let s = spring();
    let (mut x, mut v) = (s.x, s.v);
    let mut a = accel(&s, x, v);
    for _ in 0..STEPS {
        x += DT * v + 0.5 * DT * DT * a;
        let next = accel(&s, x, v + DT * a);
        v += 0.5 * DT * (a + next);
        a = next;
    }
    (x, v)
}

#[divan::bench]
fn leapfrog_generated() -> SpringState {
    generated::<_, Leapfrog<_>>(&spring())
}
#[divan::bench]
fn leapfrog_runner() -> SpringState {
    runner(&spring(), Method::Leapfrog)
}
#[divan::bench]
fn leapfrog_hand() -> (f64, f64) {
    let s = spring();
    let (mut x, mut v) = (s.x, s.v);
    let mut a = accel(&s, x, v);
    for _ in 0..STEPS {
        v += 0.5 * DT * a;
        x += DT * v;
        let next = accel(&s, x, v + 0.5 * DT * a);
        v += 0.5 * DT * next;
        a = next;
    }
    (x, v)
}

#[divan::bench]
fn rk4_generated() -> SpringState {
    generated::<_, Rk4<_>>(&spring())
}
#[divan::bench]
fn rk4_runner() -> SpringState {
    runner(&spring(), Method::Rk4)
}
#[divan::bench]
fn rk4_hand() -> (f64, f64) {
    let s = spring();
    let (mut x, mut v) = (s.x, s.v);
    let f = |x: f64, v: f64| (v, accel(&s, x, v));
    for _ in 0..STEPS {
        let k1 = f(x, v);
        let k2 = f(x + 0.5 * DT * k1.0, v + 0.5 * DT * k1.1);
        let k3 = f(x + 0.5 * DT * k2.0, v + 0.5 * DT * k2.1);
        let k4 = f(x + DT * k3.0, v + DT * k3.1);
        x += DT / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
        v += DT / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
    }
    (x, v)
}
