//! The Pleiades (seven bodies, a double loop over pairs; `jacobian = false`): one evaluation of
//! f, and RK4 steps, generated against the same arithmetic on plain arrays.

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
