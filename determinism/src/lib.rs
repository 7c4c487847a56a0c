//! Full trajectories of seven scenes reduced to one hash each, so a native run and the same code
//! compiled to WebAssembly can be compared bit for bit (issue 26: cross-platform determinism).
//!
//! Each hash is an [`odyn::Fingerprint`] (FNV-1a, 64-bit) over the IEEE bits of every recorded `f64` — every sample's
//! time and state, every event's time and states — so one differing last bit anywhere changes
//! it. Natively, `cargo run -p odyn-determinism --features deterministic` prints them; the
//! WebAssembly module exports them to `run.mjs`; `scripts/determinism.sh` builds both and
//! compares. With odyn's `deterministic` feature every transcendental function is the `libm`
//! crate's on both sides; without it each side uses its platform's and the hashes may differ.

use odyn::Fingerprint;
use odyn::prelude::*;
use scenes::{DoublePendulum, GrayScott, Lorenz, LorenzState, Sheet, Spring};

/// A scene: its name and what computes its hash.
type Scene = (&'static str, fn() -> odyn::Result<u64>);

/// The scenes, in the order both sides print them.
const SCENES: [Scene; 7] = [
    ("spring_explicit_euler", spring_explicit_euler),
    ("spring_symplectic_euler", spring_symplectic_euler),
    ("double_pendulum_rk4", double_pendulum_rk4),
    ("lorenz_dop853_events", lorenz_dop853_events),
    ("gray_scott_64_explicit", gray_scott_explicit),
    ("cloth_implicit_euler", cloth_implicit_euler),
    ("sph_dam_break", sph_dam_break),
];

/// Every scene's name and hash; a scene whose run failed hashes to 0 (and prints its error on
/// a native run), which never matches a successful run's hash.
pub fn hashes() -> Vec<(&'static str, u64)> {
    (0..SCENES.len())
        .map(|i| (SCENES[i].0, hash_of(i)))
        .collect()
}

fn hash_of(i: usize) -> u64 {
    match SCENES[i].1() {
        Ok(hash) => hash,
        Err(error) => {
            #[cfg(not(target_arch = "wasm32"))]
            eprintln!("{}: {error}", SCENES[i].0);
            #[cfg(target_arch = "wasm32")]
            let _ = error;
            0
        }
    }
}

/// The spring lab's explicit Euler, dt = 0.016, 1 000 steps.
fn spring_explicit_euler() -> odyn::Result<u64> {
    let run = Spring::released()
        .simulate()
        .integrator(Method::ExplicitEuler)
        .dt(0.016)
        .steps(1000)
        .run()?;
    Ok(Fingerprint::of_trajectory(&run))
}

/// The spring lab's symplectic Euler, dt = 0.016, 1 000 steps.
fn spring_symplectic_euler() -> odyn::Result<u64> {
    let run = Spring::released()
        .simulate()
        .integrator(Method::SymplecticEuler)
        .dt(0.016)
        .steps(1000)
        .run()?;
    Ok(Fingerprint::of_trajectory(&run))
}

/// The double pendulum under RK4 (sin and cos of the angles at every stage), dt = 0.001, 10 s.
fn double_pendulum_rk4() -> odyn::Result<u64> {
    let run = DoublePendulum::released()
        .simulate()
        .integrator(Method::Rk4)
        .dt(0.001)
        .steps(10_000)
        .record_every(10)
        .run()?;
    Ok(Fingerprint::of_trajectory(&run))
}

/// Lorenz under DOP853 (its controller takes `powf` of the error every step) at rtol 1e-9, to
/// t = 20, with every crossing of z = 25 located on the dense output.
fn lorenz_dop853_events() -> odyn::Result<u64> {
    let crossing = Event::crossing("z = 25", |_, s: &LorenzState| s.z - 25.0);
    let run = Lorenz::classic()
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-9, 1e-9)
        .duration(20.0)
        .event(crossing)
        .run()?;
    Ok(Fingerprint::of_trajectory(&run))
}

/// Gray–Scott at Pearson's set-up on 64², explicit Euler at dt = 1, 500 steps.
fn gray_scott_explicit() -> odyn::Result<u64> {
    let run = GrayScott::pearson(64, 0.04, 0.06)?
        .simulate()
        .integrator(Method::ExplicitEuler)
        .dt(1.0)
        .steps(500)
        .record_every(100)
        .run()?;
    Ok(Fingerprint::of_trajectory(&run))
}

/// The falling cloth at 12², implicit Euler at dt = 1/60 for one second: faer's sparse
/// Cholesky every step. At 32² the trajectories part: faer picks its dense kernels by CPU
/// (FMA and AVX2 or AVX-512 on x86-64, other sums in another order on WebAssembly) once its
/// supernodes are big enough to use them, so the bits of big sparse factorizations are not
/// portable (the guide's chapter *Determinism and the browser lab*).
fn cloth_implicit_euler() -> odyn::Result<u64> {
    let (cloth, _) = Sheet::falling(12).build();
    let run = cloth
        .simulate()
        .integrator(Method::ImplicitEuler)
        .dt(1.0 / 60.0)
        .steps(60)
        .record_every(10)
        .run()?;
    Ok(Fingerprint::of_trajectory(&run))
}

/// The SPH dam break at 12 particles across the column, 200 steps each at the stable dt of
/// the moment.
fn sph_dam_break() -> odyn::Result<u64> {
    let mut sph = scenes::dam_break(0.1, 12)?;
    let mut hash = Fingerprint::new();
    for _ in 0..200 {
        let dt = sph.stable_dt();
        hash.add(dt);
        sph.step(dt)?;
    }
    for (x, v) in sph.x.iter().zip(&sph.v) {
        hash.extend(x.iter().chain(v.iter()));
    }
    hash.extend(sph.densities());
    Ok(hash.finish())
}

/// The number of scenes (for the WebAssembly host).
#[unsafe(no_mangle)]
pub extern "C" fn odyn_scene_count() -> u32 {
    SCENES.len() as u32
}

/// Scene `i`'s hash, 0 if its run failed or there is no scene `i`.
#[unsafe(no_mangle)]
pub extern "C" fn odyn_scene_hash(i: u32) -> u64 {
    if (i as usize) < SCENES.len() {
        hash_of(i as usize)
    } else {
        0
    }
}

/// Where scene `i`'s name starts in memory (UTF-8, [`odyn_scene_name_len`] bytes).
#[unsafe(no_mangle)]
pub extern "C" fn odyn_scene_name(i: u32) -> *const u8 {
    SCENES.get(i as usize).map_or("".as_ptr(), |s| s.0.as_ptr())
}

/// The length of scene `i`'s name in bytes.
#[unsafe(no_mangle)]
pub extern "C" fn odyn_scene_name_len(i: u32) -> u32 {
    SCENES.get(i as usize).map_or(0, |s| s.0.len() as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every scene runs, and twice in one process gives the same hash (the hash covers the
    /// whole trajectory: `odyn::Fingerprint`'s tests show one last bit changes it).
    #[test]
    fn every_scene_runs_and_repeats_itself() {
        let first = hashes();
        assert!(first.iter().all(|&(_, h)| h != 0), "{first:x?}");
        assert_eq!(first, hashes());
    }
}
