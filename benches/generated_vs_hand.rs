//! 10⁶ steps of generated models against the same arithmetic written by hand, per integrator.
//!
//! `cargo bench --bench generated_vs_hand`. Each pair runs side by side in one process; compare
//! medians within a pair (the machine is shared, so absolute times drift between runs).
//! `generated` drives the integrator directly; `runner` is the full `Simulation::run` with its
//! per-step divergence check and no recording.

use std::hint::black_box;

use odyn::integrators::{
    ExplicitEuler, Integrator, Leapfrog, PositionVerlet, Rk4, SymplecticEuler, VelocityVerlet,
};
use odyn::prelude::*;
use odyn::{NewtonOptions, Stats};

const STEPS: u64 = 1_000_000;
const DT: f64 = 1e-3;

use scenes::*;

fn main() {
    divan::main();
}

fn spring() -> Spring {
    black_box(Spring::released())
}

fn lorenz() -> Lorenz {
    black_box(Lorenz {
        x: 1.0,
        y: 1.0,
        z: 1.0,
        sigma: 10.0,
        rho: 28.0,
        beta: 8.0 / 3.0,
    })
}

/// Steps a model with integrator `I` through the `Integrator` trait, [`STEPS`] steps of [`DT`].
fn generated<M: Model, I: Integrator<M>>(model: &M) -> M::State {
    stepped::<M, I>(model, STEPS, DT)
}

/// `steps` steps of `dt` with integrator `I` through the `Integrator` trait.
fn stepped<M: Model, I: Integrator<M>>(model: &M, steps: u64, dt: f64) -> M::State {
    let mut state = model.state();
    let mut scratch = state.clone();
    let mut stats = Stats::default();
    let mut integrator = I::start(model, 0.0, &state, &NewtonOptions::default(), &mut stats)
        .expect("a fixed-size model always starts");
    for n in 0..steps {
        // Explicit steps cannot fail; the `Result` is for implicit ones.
        let _ = integrator.step(
            model,
            n as f64 * dt,
            dt,
            &mut state,
            &mut scratch,
            &mut stats,
        );
    }
    state
}

/// The full runner: validation, per-step divergence check, first and last samples recorded.
fn runner<M: Model>(model: &M, method: Method) -> M::State {
    let run = model
        .simulate()
        .integrator(method)
        .dt(DT)
        .steps(STEPS)
        .record_every(u64::MAX)
        .run()
        .unwrap();
    run.last().state.clone()
}

mod spring {
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
}

mod lorenz {
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
}

/// The Pleiades (seven bodies, a double loop over pairs; `jacobian = false`): one evaluation of
/// f, and RK4 steps, generated against the same arithmetic on plain arrays.
mod pleiades {
    use super::*;

    /// Fewer steps than the small models: one Pleiades step costs ~100× a spring step.
    const STEPS: u64 = 10_000;
    const DT: f64 = 1e-4;
    const B: usize = 7;

    /// f on the layout (x, y, u, v), each seven wide.
    fn f(p: &Pleiades, s: &[f64; 28]) -> [f64; 28] {
        let mut d = [0.0; 28];
        d[..2 * B].copy_from_slice(&s[2 * B..]);
        for i in 0..B {
            for j in (i + 1)..B {
                let dx = s[j] - s[i];
                let dy = s[B + j] - s[B + i];
                let r2 = dx * dx + dy * dy;
                let w = 1.0 / (r2 * r2.sqrt());
                d[2 * B + i] += p.m[j] * w * dx;
                d[3 * B + i] += p.m[j] * w * dy;
                d[2 * B + j] -= p.m[i] * w * dx;
                d[3 * B + j] -= p.m[i] * w * dy;
            }
        }
        d
    }

    fn start() -> [f64; 28] {
        let p = Pleiades::start();
        let mut s = [0.0; 28];
        for (i, part) in [p.x, p.y, p.u, p.v].iter().enumerate() {
            s[B * i..B * (i + 1)].copy_from_slice(part);
        }
        s
    }

    #[divan::bench]
    fn derivative_generated(bencher: divan::Bencher) {
        let p = black_box(Pleiades::start());
        let state = p.state();
        let mut d = state;
        bencher.bench_local(|| {
            p.derivative(0.0, black_box(&state), &mut d);
            black_box(&d);
        });
    }
    #[divan::bench]
    fn derivative_hand(bencher: divan::Bencher) {
        let p = black_box(Pleiades::start());
        let s = start();
        bencher.bench_local(|| black_box(f(&p, black_box(&s))));
    }

    #[divan::bench]
    fn rk4_generated() -> PleiadesState {
        stepped::<_, Rk4<_>>(&black_box(Pleiades::start()), STEPS, DT)
    }
    /// DOP853 to t = 3 at rtol = atol = 1.78e-12 (the peers' 1e-9 target, 362 steps),
    /// recording only the ends, with or without the dense output an adaptive run keeps by
    /// default (`peers/benches/adaptive.rs` runs without).
    fn dop853(dense: bool) -> PleiadesState {
        let run = black_box(Pleiades::start())
            .simulate()
            .integrator(Method::Dop853)
            .tolerances(1.78e-12, 1.78e-12)
            .duration(3.0)
            .record_every(u64::MAX)
            .dense_output(dense)
            .run()
            .unwrap();
        run.last().state
    }
    #[divan::bench(sample_count = 20)]
    fn dop853_dense() -> PleiadesState {
        dop853(true)
    }
    #[divan::bench(sample_count = 20)]
    fn dop853_no_dense() -> PleiadesState {
        dop853(false)
    }
    #[divan::bench]
    fn rk4_hand() -> [f64; 28] {
        let p = black_box(Pleiades::start());
        let mut y = start();
        let axpy = |y: &[f64; 28], a: f64, k: &[f64; 28]| std::array::from_fn(|i| y[i] + a * k[i]);
        for _ in 0..STEPS {
            let k1 = f(&p, &y);
            let k2 = f(&p, &axpy(&y, 0.5 * DT, &k1));
            let k3 = f(&p, &axpy(&y, 0.5 * DT, &k2));
            let k4 = f(&p, &axpy(&y, DT, &k3));
            for i in 0..28 {
                y[i] += DT / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        y
    }
}

/// The double pendulum (six sines and cosines an evaluation): RK4 steps, generated against the
/// same arithmetic by hand. The row that shows what the `deterministic` feature's `libm`
/// functions cost (`cargo bench --bench generated_vs_hand --features odyn/deterministic`).
mod double_pendulum {
    use super::*;

    const STEPS: u64 = 100_000;

    /// The model's accelerations, written as `scenes/src/pendulums.rs` writes them.
    fn f(p: &DoublePendulum, [t1, t2, w1, w2]: [f64; 4]) -> [f64; 4] {
        let (m1, m2, l1, l2, g) = (p.m1, p.m2, p.l1, p.l2, p.g);
        let d = t1 - t2;
        let den = 2.0 * m1 + m2 - m2 * (2.0 * d).cos();
        let a1 = (-g * (2.0 * m1 + m2) * t1.sin()
            - m2 * g * (t1 - 2.0 * t2).sin()
            - 2.0 * d.sin() * m2 * (w2 * w2 * l2 + w1 * w1 * l1 * d.cos()))
            / (l1 * den);
        let a2 = 2.0
            * d.sin()
            * (w1 * w1 * l1 * (m1 + m2) + g * (m1 + m2) * t1.cos() + w2 * w2 * l2 * m2 * d.cos())
            / (l2 * den);
        [w1, w2, a1, a2]
    }

    fn axpy(y: [f64; 4], a: f64, k: [f64; 4]) -> [f64; 4] {
        std::array::from_fn(|i| y[i] + a * k[i])
    }

    #[divan::bench(sample_count = 20)]
    fn rk4_generated(bencher: divan::Bencher) {
        let p = black_box(DoublePendulum::released());
        bencher.bench_local(|| stepped::<_, Rk4<_>>(&p, STEPS, DT));
    }
    #[divan::bench(sample_count = 20)]
    fn rk4_hand(bencher: divan::Bencher) {
        let p = black_box(DoublePendulum::released());
        bencher.bench_local(|| {
            let mut y = [p.theta1, p.theta2, p.omega1, p.omega2];
            for _ in 0..STEPS {
                let k1 = f(&p, y);
                let k2 = f(&p, axpy(y, 0.5 * DT, k1));
                let k3 = f(&p, axpy(y, 0.5 * DT, k2));
                let k4 = f(&p, axpy(y, DT, k3));
                for i in 0..4 {
                    y[i] += DT / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
                }
            }
            y
        });
    }
}
