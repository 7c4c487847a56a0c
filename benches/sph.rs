//! One SPH step of the dam break (`examples/sph.rs`) at 10, 20, 40 and 80 particles across the
//! column (200 to 12 800 fluid particles, plus the walls), after 100 steps of collapse.
//! `cargo bench --bench sph`; the cost per step should grow about linearly with the particle
//! count (a uniform-grid neighbour search: each particle visits a fixed number of cells).

use odyn::sph::Sph;

fn main() {
    divan::main();
}

fn dam_break(resolution: usize) -> Sph {
    let mut sph = scenes::dam_break(0.2, resolution).expect("valid dam break");
    for _ in 0..100 {
        sph.step(sph.stable_dt()).expect("stable step");
    }
    sph
}

#[divan::bench(args = [10, 20, 40, 80])]
fn step(bencher: divan::Bencher, resolution: usize) {
    bencher
        .with_inputs(|| dam_break(resolution))
        .bench_local_refs(|sph| sph.step(sph.stable_dt()).expect("stable step"));
}
