//! One Stable Fluids step (advection, projection) of a rising smoke plume at 32², 64², 128² and
//! 256² cells, and the projection's sparse Cholesky substitution alone. `cargo bench --bench
//! fluids`; the cost per step should grow about linearly with the cell count (advection is
//! linear; the sparse triangular solves of a 2-D Laplacian grow like N log N with nested
//! dissection ordering, AMD here).

use odyn::fluids::{FluidOptions, StableFluids};

fn main() {
    divan::main();
}

const SIZES: [usize; 4] = [32, 64, 128, 256];
const DT: f64 = 0.02;

/// The `smoke` example's plume on an n×n grid after 20 steps.
fn plume(n: usize) -> StableFluids {
    let h = 1.0 / n as f64;
    let mut fluid = StableFluids::new(FluidOptions {
        nx: n,
        ny: n,
        cell: h,
        viscosity: 0.0,
        buoyancy: 4.0,
    })
    .expect("valid grid");
    for _ in 0..20 {
        for j in 0..n {
            for i in 0..n {
                let (x, y) = ((i as f64 + 0.5) * h, (j as f64 + 0.5) * h);
                if (x - 0.5).powi(2) + (y - 0.12).powi(2) < 0.06f64.powi(2) {
                    fluid.density[i + j * n] = 1.0;
                    fluid.v[i + j * n] = 1.0;
                }
            }
        }
        fluid.step(DT).expect("finite plume");
    }
    fluid
}

#[divan::bench(args = SIZES)]
fn step(bencher: divan::Bencher, n: usize) {
    bencher
        .with_inputs(|| plume(n))
        .bench_local_refs(|fluid| fluid.step(DT).expect("finite plume"));
}

#[divan::bench(args = SIZES)]
fn projection(bencher: divan::Bencher, n: usize) {
    bencher
        .with_inputs(|| plume(n))
        .bench_local_refs(|fluid| fluid.project().expect("finite plume"));
}
