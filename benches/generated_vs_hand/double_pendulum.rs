//! The double pendulum (six sines and cosines an evaluation): RK4 steps, generated against the
//! same arithmetic by hand. The row that shows what the `deterministic` feature's `libm`
//! functions cost (`cargo bench --bench generated_vs_hand --features odyn/deterministic`).

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
