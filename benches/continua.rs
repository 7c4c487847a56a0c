//! One step of each continuum method at a common resolution — Martin & Moyce's dam break
//! (a = 0.2 m) with 40 particles across the column (3 200 of them), and a grid of 20 cells
//! across it (a room 5a × 3a: 100 × 60 cells) — after 50 steps of collapse:
//!
//! - `sph`: weakly compressible SPH (`scenes::dam_break`, 40 particles across, plus walls);
//! - `flip`, `apic`: the FLIP/APIC liquid (`scenes::flip_dam_break`, 20 cells across);
//! - `mpm`: MLS-MPM water (`scenes::hybrid::mpm_dam_break`, 20 cells across);
//! - `stable_fluids`: Stam's Stable Fluids on the same 100 × 60 grid (a smoke plume: it has no
//!   free surface to break a dam with).
//!
//! `cargo bench --bench continua`. A step is not the same span of time for all: SPH and MPM's
//! weakly compressible liquids step at their sound speed's limit, FLIP at the flow's;
//! `examples/continua.rs` counts the steps each takes to T = 3.4 and prints the cost per
//! simulated second beside each one's front error.

use odyn::fluids::{FluidOptions, StableFluids};
use odyn::hybrid::Transfer;

fn main() {
    divan::main();
}

const A: f64 = 0.2;

#[divan::bench]
fn sph(bencher: divan::Bencher) {
    let mut sph = scenes::dam_break(A, 40).expect("the dam break");
    for _ in 0..50 {
        sph.step(sph.stable_dt()).expect("a stable step");
    }
    bencher.bench_local(|| sph.step(sph.stable_dt()).expect("a stable step"));
}

fn flip(bencher: divan::Bencher, transfer: Transfer) {
    let mut flip = scenes::flip_dam_break(A, 20, transfer).expect("the dam break");
    for _ in 0..50 {
        flip.step(flip.stable_dt()).expect("a stable step");
    }
    bencher.bench_local(|| flip.step(flip.stable_dt()).expect("a stable step"));
}

#[divan::bench]
fn flip_095(bencher: divan::Bencher) {
    flip(bencher, Transfer::Blend { flip: 0.95 });
}

#[divan::bench]
fn apic(bencher: divan::Bencher) {
    flip(bencher, Transfer::Apic);
}

#[divan::bench]
fn mpm(bencher: divan::Bencher) {
    let mut mpm = scenes::hybrid::mpm_dam_break(A, 20).expect("the dam break");
    for _ in 0..50 {
        mpm.step(mpm.stable_dt()).expect("a stable step");
    }
    bencher.bench_local(|| mpm.step(mpm.stable_dt()).expect("a stable step"));
}

#[divan::bench]
fn stable_fluids(bencher: divan::Bencher) {
    let (nx, ny) = (100, 60);
    let h = A / 20.0;
    let mut fluid = StableFluids::new(FluidOptions {
        nx,
        ny,
        cell: h,
        viscosity: 0.0,
        buoyancy: 4.0,
    })
    .expect("a valid grid");
    let dt = 0.5 * h;
    for _ in 0..50 {
        for i in 45..55 {
            fluid.density[i + 2 * nx] = 1.0;
        }
        fluid.step(dt).expect("a finite plume");
    }
    bencher.bench_local(|| fluid.step(dt).expect("a finite plume"));
}
