//! Particle models: kernels differentiated against finite differences, the assembled sparse
//! Newton matrix against a dense finite-difference one, energy and equilibrium of a hanging cloth
//! under implicit Euler, one symbolic factorization per run, and typed topology errors.

use odyn::LinearWork;
use odyn::integrators::ImplicitEuler;
use odyn::nalgebra::{SVector, Vector2, Vector3};
use odyn::particles::{ParticleJacobian, ParticleState, ParticleSystem, Spring};
use odyn::prelude::*;
use odyn::{Error, Jacobian, NewtonOptions, ParticleSolve, Stepper};
use scenes::{Hang, Sheet};

pub(crate) use scenes::Cloth;

/// An n×n cloth of side 1 m hanging in the x–y plane, top row at y = 0, 1 kg in all, springs of
/// stiffness `k` and `damping`, air drag `drag` on each particle (`scenes/src/cloth.rs`).
pub(crate) fn cloth(n: usize, k: f64, damping: f64, drag: f64) -> Cloth {
    let sheet = Sheet {
        n,
        stiffness: k,
        damping,
        particle_mass: 1.0 / (n * n) as f64,
        particle_drag: drag,
        hang: Hang::Vertical,
    };
    sheet.build().0
}

/// A deterministic pseudo-random number in [-1, 1) (SplitMix64).
fn noise(seed: &mut u64) -> f64 {
    *seed = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *seed;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    2.0 * (z >> 11) as f64 / (1u64 << 53) as f64 - 1.0
}

/// The cloth's state, every component shaken by up to `amount`.
pub(crate) fn shaken(model: &Cloth, amount: f64, seed: u64) -> ParticleState<3> {
    let mut state = model.state();
    let mut seed = seed;
    for c in state.as_mut_slice() {
        *c += amount * noise(&mut seed);
    }
    state
}

/// The forces of `model` at `state` as one flat vector.
fn forces<M: ParticleSystem<3>>(model: &M, state: &ParticleState<3>) -> Vec<f64> {
    model
        .net_forces(0.0, state)
        .iter()
        .flat_map(|f| f.iter().copied().collect::<Vec<_>>())
        .collect()
}

/// ∂f/∂x and ∂f/∂v by central differences, h = 1e-6: truncation O(h²·f‴) and round-off
/// O(ε·|f|/h) both near 1e-9 relative at these magnitudes.
fn central_force_jacobians<M: ParticleSystem<3>>(
    model: &M,
    state: &ParticleState<3>,
) -> [Vec<Vec<f64>>; 2] {
    let n = state.as_slice().len() / 2;
    let h = 1e-6;
    let column = |index: usize| {
        let (mut plus, mut minus) = (state.clone(), state.clone());
        plus.as_mut_slice()[index] += h;
        minus.as_mut_slice()[index] -= h;
        let (fp, fm) = (forces(model, &plus), forces(model, &minus));
        fp.iter()
            .zip(&fm)
            .map(|(a, b)| (a - b) / (2.0 * h))
            .collect::<Vec<_>>()
    };
    [
        (0..n).map(column).collect(),
        (n..2 * n).map(column).collect(),
    ]
}

/// The generated ∂f/∂x and ∂f/∂v of `model` at `state` against central differences, each
/// within 1e-6 of its largest entry.
fn assert_force_jacobians_match<M>(model: &M, state: &ParticleState<3>, context: &str)
where
    M: ParticleSystem<3> + Jacobian<Matrix = ParticleJacobian<3>>,
{
    let mut jacobian = model.jacobian_matrix(state);
    model.jacobian(0.0, state, &mut jacobian);
    let (dx, dv) = jacobian.force_jacobians();
    let [fd_x, fd_v] = central_force_jacobians(model, state);
    for (exact, numeric) in [(&dx, &fd_x), (&dv, &fd_v)] {
        let scale = exact.norm_max();
        for (column, values) in numeric.iter().enumerate() {
            for (row, value) in values.iter().enumerate() {
                let e = exact[(row, column)];
                assert!(
                    (e - value).abs() <= 1e-6 * scale,
                    "{context} ({row}, {column}): generated {e}, central {value}"
                );
            }
        }
    }
}

#[test]
fn kernel_blocks_match_central_differences() {
    // Stretched, sheared and moving: every term of both kernels is non-zero.
    let model = cloth(4, 1e3, 2.0, 0.3);
    for seed in 1..=5 {
        let state = shaken(&model, 0.05, seed);
        assert_force_jacobians_match(&model, &state, &format!("seed {seed}"));
    }
}

#[test]
fn assembled_newton_matrix_of_a_4x4_cloth_equals_dense_finite_differences() {
    let model = cloth(4, 1e4, 5.0, 0.1);
    let state = shaken(&model, 0.02, 7);
    let h = 1.0 / 60.0;
    let mut jacobian = model.jacobian_matrix(&state);
    model.jacobian(0.0, &state, &mut jacobian);
    let sparse = jacobian.newton_matrix(h).to_dense();
    let [fd_x, fd_v] = central_force_jacobians(&model, &state);
    let n = 3 * 16;
    let pinned = |k: usize| model.pinned.contains(&(k / 3));
    let mut largest = 0.0f64;
    let mut worst = 0.0f64;
    for row in 0..n {
        for column in 0..n {
            // M − h·∂f/∂v − h²·∂f/∂x, with the pinned particles' rows and columns replaced by M.
            let mass = if row == column {
                model.mass[row / 3]
            } else {
                0.0
            };
            let expected = if pinned(row) || pinned(column) {
                mass
            } else {
                mass - h * fd_v[column][row] - h * h * fd_x[column][row]
            };
            largest = largest.max(expected.abs());
            worst = worst.max((sparse[(row, column)] - expected).abs());
        }
    }
    assert!(worst <= 1e-7 * largest, "worst {worst:e} of {largest:e}");
    // 16 diagonal blocks plus two per spring between free particles, 9 entries each.
    let free_links = model
        .springs
        .iter()
        .filter(|s| !model.pinned.contains(&s.a) && !model.pinned.contains(&s.b))
        .count();
    assert_eq!(jacobian.nonzeros(), 9 * (16 + 2 * free_links));
}

#[test]
fn undamped_cloth_under_implicit_euler_never_gains_energy() {
    // No spring damping, no drag: the exact flow conserves energy; implicit Euler may only
    // dissipate it (its amplification factor 1/(1 − hλ) has modulus < 1 for every λ of a
    // conservative linearization, Hairer & Wanner II §IV.3).
    let model = cloth(6, 1e4, 0.0, 0.0);
    let run = model.simulate().duration(2.0).run().unwrap();
    let energies: Vec<f64> = run.samples.iter().map(|s| s.energy.unwrap()).collect();
    for pair in energies.windows(2) {
        assert!(
            pair[1] <= pair[0] + 1e-9 * pair[0].abs().max(1.0),
            "{} -> {}",
            pair[0],
            pair[1]
        );
    }
    assert!(energies.last().unwrap() < &energies[0]);
}

#[test]
fn damped_pinned_cloth_settles_to_static_equilibrium() {
    let model = cloth(6, 1e3, 2.0, 0.2);
    let run = model.simulate().duration(20.0).run().unwrap();
    assert_settled(&model, &run.samples.last().unwrap().state, 1e-6);
}

/// Every free particle's net force is below `fraction` of its weight and its velocity below 1e-6
/// m/s, and the pinned corners carry the whole weight between them: the net force on them (what
/// their supports must cancel) is the cloth's total weight, to 1e-6 of it.
pub(crate) fn assert_settled(model: &Cloth, last: &ParticleState<3>, fraction: f64) {
    let forces = model.net_forces(0.0, last);
    let weight = model.mass[0] * 9.81;
    for (i, (f, v)) in forces.iter().zip(last.velocities()).enumerate() {
        if model.pinned.contains(&i) {
            continue;
        }
        assert!(
            f.norm() < fraction * weight,
            "particle {i}: |f| = {:e}",
            f.norm()
        );
        assert!(v.norm() < 1e-6, "particle {i}: |v| = {:e}", v.norm());
    }
    let held: Vector3<f64> = model.pinned.iter().map(|&p| forces[p]).sum();
    let total = model.mass.iter().sum::<f64>() * 9.81;
    assert!(
        (held + Vector3::new(0.0, total, 0.0)).norm() < 1e-6 * total,
        "{held:?}"
    );
}

/// Runs `steps` implicit steps of `model` and returns its factorization counts and Jacobian
/// evaluations.
fn factorization_counts(model: &Cloth, newton: NewtonOptions, steps: u32) -> (LinearWork, u64) {
    let mut stepper = Stepper::<Cloth, ImplicitEuler<Cloth>>::with_newton(
        model,
        model.state(),
        0.0,
        1.0 / 60.0,
        &newton,
    )
    .unwrap();
    for _ in 0..steps {
        stepper.step().unwrap();
    }
    (
        stepper.integrator().matrix().factorizations(),
        stepper.stats().jacobian_evaluations,
    )
}

#[test]
fn the_symbolic_factorization_is_computed_once_per_run() {
    // Without spring damping the Newton matrix M − h·∂f/∂v − h²·∂f/∂x is symmetric (conservative
    // springs, isotropic drag): one symbolic Cholesky for the run, one numeric factorization per
    // Newton iteration, no LU.
    let undamped = cloth(5, 1e4, 0.0, 0.1);
    // Full Newton, as configured (the default, said explicitly).
    let full = NewtonOptions {
        particle_solve: ParticleSolve::Newton,
        ..NewtonOptions::default()
    };
    for newton in [full, NewtonOptions::linearized()] {
        let (counts, jacobians) = factorization_counts(&undamped, newton, 60);
        assert_eq!(counts.symbolic_cholesky, 1, "{counts:?}");
        assert_eq!(counts.symbolic_lu, 0, "{counts:?}");
        assert_eq!(counts.cholesky_failed, 0, "{counts:?}");
        assert_eq!(counts.cholesky, jacobians, "{counts:?}");
        if newton.linearized {
            assert_eq!(jacobians, 60);
        } else {
            // At least one iteration per step, a second wherever the first moved the state.
            assert!(jacobians > 60, "{jacobians}");
        }
    }
    // Damping along a moving spring has an unsymmetric ∂f/∂x: LU takes over once the cloth
    // moves, its symbolic analysis made once and kept.
    let damped = cloth(5, 1e4, 2.0, 0.1);
    let (counts, jacobians) = factorization_counts(&damped, full, 60);
    assert_eq!(
        (counts.symbolic_cholesky, counts.symbolic_lu),
        (1, 1),
        "{counts:?}"
    );
    assert_eq!(counts.cholesky + counts.lu, jacobians, "{counts:?}");
    assert!(counts.lu > 0 && counts.cholesky > 0, "{counts:?}");
    // A run reports the same counts in its stats (the `linear` section), and each of its
    // factorizations is one of them.
    let run = damped
        .simulate()
        .integrator(Method::ImplicitEuler)
        .newton(full)
        .dt(1.0 / 60.0)
        .steps(60)
        .record_every(u64::MAX)
        .run()
        .unwrap();
    assert_eq!(run.stats.linear, counts, "{}", run.stats);
    assert_eq!(
        run.stats.linear.cholesky + run.stats.linear.lu,
        run.stats.factorizations,
        "{}",
        run.stats
    );
}

#[test]
fn bad_topology_is_a_typed_error() {
    let expect = |model: &Cloth, what: &str| match model.simulate().steps(1).run() {
        Err(Error::BadModel { what: got, .. }) => assert_eq!(got, what),
        other => panic!("expected BadModel at {what}, got {other:?}"),
    };
    let mut out_of_range = cloth(3, 1e3, 0.0, 0.0);
    out_of_range.springs[4].b = 9;
    expect(&out_of_range, "springs[4]");
    let mut zero_rest = cloth(3, 1e3, 0.0, 0.0);
    zero_rest.springs[2].rest = 0.0;
    expect(&zero_rest, "springs[2]");
    let mut massless = cloth(3, 1e3, 0.0, 0.0);
    massless.mass[5] = 0.0;
    expect(&massless, "mass[5]");
    let mut self_link = cloth(3, 1e3, 0.0, 0.0);
    self_link.springs[0].b = self_link.springs[0].a;
    expect(&self_link, "springs[0]");
    let mut bad_pin = cloth(3, 1e3, 0.0, 0.0);
    bad_pin.pinned[1] = 100;
    expect(&bad_pin, "pinned[1]");
    let mut short = cloth(3, 1e3, 0.0, 0.0);
    short.mass.pop();
    expect(&short, "`mass`");
    // The message names the model, the link and the problem.
    let message = zero_rest.simulate().steps(1).run().unwrap_err().to_string();
    assert_eq!(
        message,
        "`Cloth` cannot be simulated: springs[2] has rest length 0; it must be finite and positive"
    );
}

/// A 2-D chain under gravity without velocity-dependent forces: every method runs on it.
#[system(integrator = PositionVerlet, dt = 1e-3)]
struct Chain {
    #[position]
    x: Vec<Vector2<f64>>,
    #[velocity]
    v: Vec<Vector2<f64>>,
    #[mass]
    m: Vec<f64>,
    #[pinned]
    fixed: Vec<usize>,
    links: Vec<Spring>,
    g: f64,
}

#[system]
impl Chain {
    #[pair(links)]
    fn spring(&self, s: &Spring, xa: Vector2<f64>, xb: Vector2<f64>) -> Vector2<f64> {
        let d = xb - xa;
        d.normalize() * (s.stiffness * (d.norm() - s.rest))
    }

    #[particle]
    fn weight(&self, i: usize, _x: Vector2<f64>) -> Vector2<f64> {
        Vector2::new(0.0, -self.g * self.m[i])
    }

    fn potential(&self) -> f64 {
        let springs: f64 = self
            .links
            .iter()
            .map(|s| 0.5 * s.stiffness * ((self.x[s.b] - self.x[s.a]).norm() - s.rest).powi(2))
            .sum();
        let gravity: f64 = self
            .x
            .iter()
            .zip(&self.m)
            .map(|(x, m)| m * self.g * x.y)
            .sum();
        springs + gravity
    }
}

fn chain(n: usize) -> Chain {
    let x: Vec<_> = (0..n).map(|i| Vector2::new(0.1 * i as f64, 0.0)).collect();
    Chain {
        links: (0..n - 1)
            .map(|i| Spring::at_rest(&x, i, i + 1, 100.0, 0.0))
            .collect(),
        v: vec![Vector2::zeros(); n],
        m: vec![0.1; n],
        fixed: vec![0],
        g: 9.81,
        x,
    }
}

#[test]
fn every_method_runs_a_particle_model_and_pinned_particles_stay_put() {
    let model = chain(8);
    let start = model.state();
    // ω_max ≈ 2√(k/m) = 63 rad/s: dt = 1e-3 is well inside every explicit limit except explicit
    // Euler's (none), which still grows only by (1 + ω²dt²)^(n/2) ≈ 1.2 over 100 steps.
    let mut finals = Vec::new();
    for method in Method::ALL {
        let run = model
            .simulate()
            .integrator(method)
            .dt(1e-3)
            .steps(100)
            .run()
            .unwrap();
        let last = run.samples.last().unwrap().state.clone();
        assert_eq!(last.positions()[0], start.positions()[0], "{method}");
        assert_eq!(last.velocities()[0], SVector::<f64, 2>::zeros(), "{method}");
        finals.push((method, last));
    }
    // All methods agree to their accuracy after 0.1 s (first-order ones to ~1e-2).
    let reference = &finals.iter().find(|(m, _)| *m == Method::Rk4).unwrap().1;
    for (method, last) in &finals {
        let diff = last
            .positions()
            .iter()
            .zip(reference.positions())
            .map(|(a, b)| (a - b).norm())
            .fold(0.0, f64::max);
        assert!(diff < 2e-2, "{method}: {diff}");
    }
}

/// The sparse velocity-form solve of `factorize` and `solve` against a dense LU of the full
/// first-order Newton matrix I − h·J, J = [[0, I], [M⁻¹∂f/∂x, M⁻¹∂f/∂v]] (pinned rows zero).
fn dense_newton_solve(model: &Cloth, state: &ParticleState<3>, h: f64, b: &[f64]) -> Vec<f64> {
    let mut jacobian = model.jacobian_matrix(state);
    model.jacobian(0.0, state, &mut jacobian);
    let (dx, dv) = jacobian.force_jacobians();
    let n = state.as_slice().len() / 2;
    let mut full = odyn::nalgebra::DMatrix::<f64>::identity(2 * n, 2 * n);
    for r in 0..n {
        full[(r, n + r)] -= h;
        let p = r / 3;
        if model.pinned.contains(&p) {
            continue;
        }
        for c in 0..n {
            full[(n + r, c)] -= h * dx[(r, c)] / model.mass[p];
            full[(n + r, n + c)] -= h * dv[(r, c)] / model.mass[p];
        }
    }
    let rhs = odyn::nalgebra::DVector::from_column_slice(b);
    full.lu().solve(&rhs).unwrap().as_slice().to_vec()
}

#[test]
fn sparse_velocity_solve_equals_the_dense_first_order_newton_solve_every_time() {
    use odyn::NewtonMatrix;
    let model = cloth(4, 1e3, 1.0, 0.1);
    let at_rest = model.state(); // symmetric: Cholesky
    let moving = shaken(&model, 0.02, 4); // damping makes ∂f/∂x unsymmetric: LU
    let h = 0.01;
    let mut seed = 5;
    let n = at_rest.as_slice().len() / 2;
    // Pinned particles' velocity residual is zero in every Newton iteration (their v̇ is 0).
    let b: Vec<f64> = (0..2 * n)
        .map(|k| {
            let value = noise(&mut seed);
            if k >= n && model.pinned.contains(&((k - n) / 3)) {
                0.0
            } else {
                value
            }
        })
        .collect();
    // One matrix refactorized for alternating states must match a fresh dense solve each time.
    let mut jacobian = model.jacobian_matrix(&at_rest);
    jacobian.factors();
    for state in [&at_rest, &moving, &at_rest, &moving, &moving] {
        model.jacobian(0.0, state, &mut jacobian);
        let mut sparse = b.clone();
        NewtonMatrix::factorize(&mut jacobian, h, &mut ()).expect("W is regular");
        jacobian.solve(&mut (), &mut sparse).expect("x is finite");
        let dense = dense_newton_solve(&model, state, h, &b);
        let scale = dense.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (k, (s, d)) in sparse.iter().zip(&dense).enumerate() {
            assert!(
                (s - d).abs() <= 1e-10 * scale,
                "component {k}: sparse {s}, dense {d}"
            );
        }
    }
    let counts = jacobian.factorizations();
    assert_eq!((counts.cholesky, counts.lu), (2, 3), "{counts:?}");
    assert_eq!(
        (counts.symbolic_cholesky, counts.symbolic_lu),
        (1, 1),
        "{counts:?}"
    );
}

/// Replacing the state through `Stepper::state_mut` by one of another size used to panic in the
/// force sum (`copy_from_slice` of slices of different lengths).
#[test]
fn a_replaced_state_of_another_size_is_a_typed_error() {
    let model = chain(8);
    let mut stepper = Stepper::<Chain, odyn::integrators::SymplecticEuler<_>>::new(
        &model,
        model.state(),
        0.0,
        1e-3,
    )
    .unwrap();
    stepper.step().unwrap();
    *stepper.state_mut() = chain(5).state();
    let error = stepper.step().unwrap_err();
    assert!(
        matches!(&error, Error::InvalidInput { field, .. } if field == "state")
            && error.to_string().contains("20 components")
            && error.to_string().contains("32"),
        "{error}"
    );
    // Back to a state of the model's size, it steps on.
    *stepper.state_mut() = model.state();
    stepper.step().unwrap();
    assert_eq!(stepper.steps(), 2);
}

/// Cables: links that pull only while stretched, written as an `if` on the state in the pair
/// kernel, over a random tangle in which some are taut and some slack.
#[system]
struct Cables {
    #[position]
    x: Vec<Vector3<f64>>,
    #[velocity]
    v: Vec<Vector3<f64>>,
    #[mass]
    mass: Vec<f64>,
    links: Vec<Spring>,
}

#[system]
impl Cables {
    #[pair(links)]
    fn cable(&self, s: &Spring, xa: Vector3<f64>, xb: Vector3<f64>) -> Vector3<f64> {
        let d = xb - xa;
        let length = d.norm();
        if length > s.rest {
            d * (s.stiffness * (length - s.rest) / length)
        } else {
            Vector3::zeros()
        }
    }
}

#[test]
fn a_kernel_branching_on_the_state_matches_central_differences() {
    let mut seed = 11;
    let n = 12;
    let x: Vec<Vector3<f64>> = (0..n)
        .map(|_| Vector3::new(noise(&mut seed), noise(&mut seed), noise(&mut seed)))
        .collect();
    let mut links = Vec::new();
    let (mut taut, mut slack) = (0, 0);
    for a in 0..n {
        for b in [(a + 1) % n, (a + 5) % n] {
            // A rest length within 20 % of the distance either way, but never within 1e-3 of
            // it, so central differences (h = 1e-6) do not straddle the switch.
            let distance = (x[b] - x[a]).norm();
            let mut rest = distance * (1.0 + 0.2 * noise(&mut seed));
            if (rest - distance).abs() < 1e-3 {
                rest = distance + 1e-2;
            }
            if distance > rest {
                taut += 1
            } else {
                slack += 1
            }
            links.push(Spring {
                a,
                b,
                rest,
                stiffness: 50.0,
                damping: 0.0,
            });
        }
    }
    assert!(taut > 3 && slack > 3, "{taut} taut, {slack} slack");
    let model = Cables {
        v: vec![Vector3::zeros(); n],
        mass: vec![1.0; n],
        links,
        x,
    };
    // ∂f/∂v is zero both ways: no cable reads a velocity.
    assert_force_jacobians_match(&model, &model.state(), "cables");
}
