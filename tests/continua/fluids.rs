//! Stable Fluids: the projection leaves a divergence-free field, the solver is stable far above
//! CFL 1 (no energy is created), diffusion only removes energy, and bad settings are typed
//! errors.

use odyn::Error;
use odyn::fluids::{FluidOptions, StableFluids};

/// A fluid on an n×n grid over the unit square with a smooth, strongly divergent velocity field
/// (a sum of a few sines and a source-like term).
fn stirred(n: usize, viscosity: f64) -> StableFluids {
    let h = 1.0 / n as f64;
    let mut fluid = StableFluids::new(FluidOptions {
        nx: n,
        ny: n,
        cell: h,
        viscosity,
        ..FluidOptions::default()
    })
    .unwrap();
    for j in 0..n {
        for i in 1..n {
            let (x, y) = (i as f64 * h, (j as f64 + 0.5) * h);
            fluid.u[i + j * (n + 1)] = (3.0 * x).sin() * (2.0 * y).cos() + x - 0.5;
        }
    }
    for j in 1..n {
        for i in 0..n {
            let (x, y) = ((i as f64 + 0.5) * h, j as f64 * h);
            fluid.v[i + j * n] = (5.0 * x * y).cos() - (y - 0.5) * 2.0;
        }
    }
    fluid
}

fn max_abs(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |m, x| m.max(x.abs()))
}

#[test]
fn projection_leaves_no_divergence() {
    for n in [8, 33, 64] {
        let mut fluid = stirred(n, 0.0);
        let before = max_abs(&fluid.divergence());
        fluid.project().unwrap();
        let after = max_abs(&fluid.divergence());
        eprintln!("{n}²: max |div| {before:e} → {after:e}");
        assert!(before > 1.0, "the test field is divergent ({before})");
        assert!(after <= 1e-10, "{n}²: max |div| after projection {after:e}");
        // Projection is idempotent: a divergence-free field is left as it is.
        let (u, v) = (fluid.u.clone(), fluid.v.clone());
        fluid.project().unwrap();
        let moved = u
            .iter()
            .zip(&fluid.u)
            .chain(v.iter().zip(&fluid.v))
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(
            moved <= 1e-12,
            "{n}²: a second projection moved the field by {moved:e}"
        );
    }
}

/// Semi-Lagrangian advection interpolates (it never creates new extrema) and the projection is
/// an orthogonal projection, so without forcing no step can add kinetic energy, whatever the
/// CFL number u·Δt/h. Checked over 100 steps at CFL ≥ 5, divergence-free after every step.
#[test]
fn stable_far_above_cfl_one() {
    let n = 48;
    let mut fluid = stirred(n, 0.0);
    fluid.project().unwrap();
    let h = 1.0 / n as f64;
    let dt = 5.0 * h / fluid.max_speed();
    let mut energy = fluid.kinetic_energy();
    for step in 0..100 {
        let cfl = fluid.max_speed() * dt / h;
        fluid.step(dt).unwrap();
        let now = fluid.kinetic_energy();
        assert!(
            now.is_finite() && now <= energy * (1.0 + 1e-12),
            "step {step}: {energy} → {now}"
        );
        assert!(max_abs(&fluid.divergence()) <= 1e-10, "step {step}");
        if step == 0 {
            assert!(cfl >= 5.0 * (1.0 - 1e-12), "CFL {cfl}");
        }
        energy = now;
    }
}

/// Implicit diffusion damps: each step with ν > 0 ends with no more energy than the same step
/// without it, and a large νΔt (1000 cells² a step) is still stable.
#[test]
fn diffusion_only_removes_energy() {
    let n = 24;
    let dt = 0.01;
    let mut inviscid = stirred(n, 0.0);
    let mut viscous = stirred(n, 1e-3);
    let mut huge = stirred(n, 1000.0 / (n * n) as f64 / dt);
    for f in [&mut inviscid, &mut viscous, &mut huge] {
        f.project().unwrap();
    }
    for _ in 0..20 {
        inviscid.step(dt).unwrap();
        viscous.step(dt).unwrap();
        huge.step(dt).unwrap();
        assert!(viscous.kinetic_energy() < inviscid.kinetic_energy());
        assert!(huge.kinetic_energy() < viscous.kinetic_energy());
        assert!(max_abs(&huge.divergence()) <= 1e-10);
    }
}

#[test]
fn bad_settings_are_typed_errors() {
    let with = |f: &dyn Fn(&mut FluidOptions)| {
        let mut options = FluidOptions::default();
        f(&mut options);
        StableFluids::new(options).err().map(|e| e.to_string())
    };
    assert!(with(&|o| o.nx = 2).unwrap().contains("too small"));
    assert!(with(&|o| o.ny = 0).unwrap().contains("too small"));
    // A grid beyond usize, or beyond what the machine can allocate (2⁴⁰ × 64 cells), used to
    // panic or abort on the allocation.
    assert!(
        with(&|o| o.nx = usize::MAX)
            .unwrap()
            .contains("cells is more than")
    );
    assert!(
        with(&|o| o.nx = 1 << 40)
            .unwrap()
            .contains("cells is more than")
    );
    assert!(with(&|o| o.cell = 0.0).is_some());
    assert!(with(&|o| o.cell = f64::NAN).is_some());
    assert!(with(&|o| o.viscosity = -1.0).is_some());
    assert!(with(&|o| o.buoyancy = f64::INFINITY).is_some());
    let mut fluid = StableFluids::new(FluidOptions::default()).unwrap();
    for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(fluid.step(dt).is_err(), "dt {dt}");
    }
    fluid.u.pop();
    assert!(
        fluid
            .step(0.01)
            .unwrap_err()
            .to_string()
            .contains("must keep")
    );
    fluid.u.push(0.0);
    fluid.density[5] = f64::NAN;
    assert!(
        fluid
            .step(0.01)
            .unwrap_err()
            .to_string()
            .contains("density")
    );
}

/// The field and message of an `InvalidInput`, or a panic naming what came instead.
fn invalid(result: odyn::Result<()>) -> (String, String) {
    let error = result.expect_err("expected InvalidInput");
    let message = error.to_string();
    match error {
        Error::InvalidInput { field, .. } => (field, message),
        other => panic!("expected InvalidInput, got {other}"),
    }
}

/// A cell size of 1e-200 or 1e200 used to be refused as "invalid matrix: not positive
/// definite" (the Poisson matrix held 1/h²: ∞ or 0). The projection is now solved without h,
/// so either is a working fluid; only a viscosity whose ν/h² overflows is refused, named.
#[test]
fn any_cell_size_projects_and_an_overflowing_viscosity_is_named() {
    for cell in [1e-200, 1e200] {
        let mut fluid = StableFluids::new(FluidOptions {
            nx: 8,
            ny: 8,
            cell,
            ..FluidOptions::default()
        })
        .unwrap();
        fluid.u[4 + 3 * 9] = 1.0;
        fluid.step(0.5).unwrap();
        let flux = max_abs(&fluid.divergence()) * cell;
        assert!(flux <= 1e-12 && fluid.max_speed() > 0.01, "{flux:e}");
    }
    let (field, message) = invalid(
        StableFluids::new(FluidOptions {
            cell: 1e-200,
            viscosity: 1e-3,
            ..FluidOptions::default()
        })
        .map(drop),
    );
    assert_eq!(field, "viscosity");
    assert!(
        message.contains("1e-200") && message.contains("overflows"),
        "{message}"
    );
}

/// `step(1e-310)` used to divide the divergence by Δt (1/Δt = ∞) and return Ok with NaN
/// velocities. The projection solves for Δt·p, in which Δt cancels, so a tiny step is a correct
/// one: finite and divergence-free, with or without viscosity.
#[test]
fn a_tiny_step_is_a_correct_step() {
    for viscosity in [0.0, 1e-3] {
        let mut fluid = stirred(16, viscosity);
        fluid.step(1e-310).unwrap();
        assert!(fluid.u.iter().chain(&fluid.v).all(|x| x.is_finite()));
        assert!(max_abs(&fluid.divergence()) <= 1e-10);
    }
}

/// A buoyancy of 1e300 over a step of 1e10 s overflows the velocity; it used to return Ok with
/// a non-finite state. The fields are checked after every step and the error names the step.
#[test]
fn a_step_that_overflows_is_a_typed_error_naming_it() {
    let mut fluid = StableFluids::new(FluidOptions {
        nx: 8,
        ny: 8,
        cell: 1.0 / 8.0,
        buoyancy: 1e300,
        ..FluidOptions::default()
    })
    .unwrap();
    fluid.density[3 + 3 * 8] = 1.0;
    let error = fluid.step(1e10).unwrap_err();
    assert!(
        matches!(
            error,
            Error::NotFinite {
                solver: "StableFluids",
                step: 1,
                ..
            }
        ),
        "{error:?}"
    );
    let message = error.to_string();
    assert!(
        message.contains("non-finite at step 1") && message.contains("buoyancy"),
        "{message}"
    );
}

/// The walls are solid: a velocity written into a wall face (normal to the wall) is flow
/// through it, which no pressure can remove (the divergence was 3.2e7 after a step). It is an
/// input error naming the face.
#[test]
fn the_walls_take_no_normal_velocity() {
    let n = 8;
    // The left wall's face in row 2, then the top wall's face in column 5.
    for (u, v, field) in [(2 * (n + 1), None, "u[18]"), (0, Some(5 + n * n), "v[69]")] {
        let mut fluid = stirred(n, 0.0);
        match v {
            Some(k) => fluid.v[k] = 1.0,
            None => fluid.u[u] = 1.0,
        }
        let (name, message) = invalid(fluid.step(0.01));
        assert_eq!(name, field);
        assert!(
            message.contains("wall") && message.contains("must be 0"),
            "{message}"
        );
    }
}
