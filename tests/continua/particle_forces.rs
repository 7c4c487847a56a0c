//! Implicit Euler on particle models beyond springs: the default (`ParticleSolve::Auto`, full
//! Newton) against theory on forces that are not springs — attraction, repulsion, a magnetic
//! force, softened gravity, damping — where it never gains energy and damps linear forces by
//! implicit Euler's factor; the one-step (Baraff–Witkin) form's energy gain that keeps it from
//! being the default; extreme stiffnesses, masses and steps; non-finite input and topology edge
//! cases as typed errors.

use odyn::integrators::ImplicitEuler;
use odyn::nalgebra::{Vector2, Vector3};
use odyn::particles::{ParticleState, Spring};
use odyn::prelude::*;
use odyn::{Error, Jacobian, Model, NewtonOptions, ParticleSolve, Stepper};
use scenes::Sheet;

/// The default: `ParticleSolve::Auto`.
fn auto() -> NewtonOptions {
    NewtonOptions::default()
}

/// Full Newton, named.
fn full() -> NewtonOptions {
    NewtonOptions {
        particle_solve: ParticleSolve::Newton,
        ..NewtonOptions::default()
    }
}

/// The Baraff–Witkin step set by hand, with `ParticleSolve::Newton` so `Auto` plays no part.
fn by_hand() -> NewtonOptions {
    NewtonOptions {
        linearized: true,
        definite: true,
        particle_solve: ParticleSolve::Newton,
        ..NewtonOptions::default()
    }
}

/// `steps` implicit Euler steps of `model` from `state`: every state, start included.
fn trace<M>(
    model: &M,
    state: M::State,
    dt: f64,
    steps: usize,
    newton: NewtonOptions,
) -> odyn::Result<Vec<M::State>>
where
    M: Jacobian,
    M::State: Clone,
{
    let mut stepper = Stepper::<M, ImplicitEuler<M>>::with_newton(model, state, 0.0, dt, &newton)?;
    let mut states = vec![stepper.state().clone()];
    for _ in 0..steps {
        stepper.step()?;
        states.push(stepper.state().clone());
    }
    Ok(states)
}

/// Largest |difference| of two states' components.
fn gap<const D: usize>(a: &ParticleState<D>, b: &ParticleState<D>) -> f64 {
    crate::common::max_abs_difference(a.as_slice(), b.as_slice())
}

fn bits<const D: usize>(s: &ParticleState<D>) -> Vec<u64> {
    s.as_slice().iter().map(|c| c.to_bits()).collect()
}

fn kinetic<const D: usize>(s: &ParticleState<D>, m: &[f64]) -> f64 {
    let v = s.velocities().iter().zip(m);
    v.map(|(v, m)| 0.5 * m * v.norm_squared()).sum()
}

// ---------------------------------------------------------------------------------------------
// Models.

/// 3-D, a linear pair force fₐ = k·(x_b − xₐ) on every link (k > 0 attracts: a zero-rest-length
/// spring; k < 0 repels), plus a constant pair force `push` on a (−push on b), whose Jacobian is
/// zero.
#[system(integrator = ImplicitEuler, dt = 0.01)]
#[derive(Clone, Debug)]
struct Linear3 {
    #[position]
    x: Vec<Vector3<f64>>,
    #[velocity]
    v: Vec<Vector3<f64>>,
    #[mass]
    m: Vec<f64>,
    #[pinned]
    pins: Vec<usize>,
    links: Vec<[usize; 2]>,
    k: f64,
    push: Vector3<f64>,
}

#[system]
impl Linear3 {
    #[pair(links)]
    fn pull(&self, _l: &[usize; 2], xa: Vector3<f64>, xb: Vector3<f64>) -> Vector3<f64> {
        (xb - xa) * self.k + self.push
    }
}

fn linear3(k: f64, m: f64) -> Linear3 {
    Linear3 {
        x: vec![Vector3::zeros(), Vector3::new(1.0, 0.0, 0.0)],
        v: vec![Vector3::zeros(); 2],
        m: vec![m; 2],
        pins: vec![],
        links: vec![[0, 1]],
        k,
        push: Vector3::zeros(),
    }
}

/// ½k|d|² over links + ½Σm|v|² (the push off).
fn linear3_energy(model: &Linear3, s: &ParticleState<3>) -> f64 {
    let x = s.positions();
    let springs: f64 = model
        .links
        .iter()
        .map(|[a, b]| 0.5 * model.k * (x[*b] - x[*a]).norm_squared())
        .sum();
    springs + kinetic(s, &model.m)
}

/// 3-D softened gravity between every pair listed: fₐ = G·mₐ·m_b·d/(|d|² + ε²)^{3/2}.
#[system(integrator = ImplicitEuler, dt = 0.01)]
#[derive(Clone, Debug)]
struct Gravity {
    #[position]
    x: Vec<Vector3<f64>>,
    #[velocity]
    v: Vec<Vector3<f64>>,
    #[mass]
    m: Vec<f64>,
    pairs: Vec<[usize; 2]>,
    g: f64,
    eps: f64,
}

#[system]
impl Gravity {
    #[pair(pairs)]
    fn attract(&self, l: &[usize; 2], xa: Vector3<f64>, xb: Vector3<f64>) -> Vector3<f64> {
        let d = xb - xa;
        let r2 = d.norm_squared() + self.eps * self.eps;
        d * (self.g * self.m[l[0]] * self.m[l[1]] / (r2 * r2.sqrt()))
    }
}

fn gravity_energy(model: &Gravity, s: &ParticleState<3>) -> f64 {
    let x = s.positions();
    let pot: f64 = model
        .pairs
        .iter()
        .map(|&[a, b]| {
            let r2 = (x[b] - x[a]).norm_squared() + model.eps * model.eps;
            -model.g * model.m[a] * model.m[b] / r2.sqrt()
        })
        .sum();
    pot + kinetic(s, &model.m)
}

/// Two unit masses on a circular orbit of separation 1 (G = 1: relative speed √2, period
/// 2π/√2 ≈ 4.44 s, Kepler), ε = 1e-3.
fn binary() -> Gravity {
    let u = 0.5 * 2f64.sqrt();
    Gravity {
        x: vec![Vector3::new(-0.5, 0.0, 0.0), Vector3::new(0.5, 0.0, 0.0)],
        v: vec![Vector3::new(0.0, -u, 0.0), Vector3::new(0.0, u, 0.0)],
        m: vec![1.0; 2],
        pairs: vec![[0, 1]],
        g: 1.0,
        eps: 1e-3,
    }
}

/// 2-D, particle forces only (no links): a charge in a magnetic field B ẑ, f = q·v × B =
/// qB·(v_y, −v_x), and an optional harmonic trap −κ·x.
#[system(integrator = ImplicitEuler, dt = 0.01)]
#[derive(Clone, Debug)]
struct Charges {
    #[position]
    x: Vec<Vector2<f64>>,
    #[velocity]
    v: Vec<Vector2<f64>>,
    #[mass]
    m: Vec<f64>,
    qb: f64,
    trap: f64,
}

#[system]
impl Charges {
    #[particle]
    fn lorentz(&self, x: Vector2<f64>, v: Vector2<f64>) -> Vector2<f64> {
        Vector2::new(v.y, -v.x) * self.qb - x * self.trap
    }
}

/// 2-D spring with a rest length and an isotropic damper fₐ = c·(v_b − vₐ) between the ends.
#[system(integrator = ImplicitEuler, dt = 0.01)]
#[derive(Clone, Debug)]
struct Damped2 {
    #[position]
    x: Vec<Vector2<f64>>,
    #[velocity]
    v: Vec<Vector2<f64>>,
    #[mass]
    m: Vec<f64>,
    #[pinned]
    pins: Vec<usize>,
    springs: Vec<Spring>,
    c: f64,
}

#[system]
impl Damped2 {
    #[pair(springs)]
    fn spring(
        &self,
        s: &Spring,
        xa: Vector2<f64>,
        xb: Vector2<f64>,
        va: Vector2<f64>,
        vb: Vector2<f64>,
    ) -> Vector2<f64> {
        let d = xb - xa;
        d.normalize() * (s.stiffness * (d.norm() - s.rest)) + (vb - va) * self.c
    }
}

/// A 2-D rope of `n` particles 0.05 m apart along x, pinned at 0, springs k, no damping.
fn rope(n: usize, k: f64, c: f64) -> Damped2 {
    let x: Vec<_> = (0..n).map(|i| Vector2::new(0.05 * i as f64, 0.0)).collect();
    Damped2 {
        springs: (0..n - 1)
            .map(|i| Spring::at_rest(&x, i, i + 1, k, 0.0))
            .collect(),
        v: vec![Vector2::zeros(); n],
        m: vec![0.005; n],
        pins: vec![0],
        c,
        x,
    }
}

fn spring_energy(model: &Damped2, s: &ParticleState<2>) -> f64 {
    let x = s.positions();
    let springs: f64 = model
        .springs
        .iter()
        .map(|sp| 0.5 * sp.stiffness * ((x[sp.b] - x[sp.a]).norm() - sp.rest).powi(2))
        .sum();
    springs + kinetic(s, &model.m)
}

// ---------------------------------------------------------------------------------------------
// 1. Forces that are not springs.

#[test]
fn linear_attraction_damps_by_the_implicit_euler_factor_under_both_solves() {
    // Two masses m joined by fₐ = k·d: the separation obeys d̈ = −ω²d, ω² = 2k/m; implicit Euler
    // multiplies its energy by 1/(1 + ω²h²) every step (ImplicitEuler's rustdoc; Hairer & Wanner
    // II §IV.3). k = 100, m = 1, h = 0.1: ω²h² = 2, factor 1/3. The force is linear, so one
    // Newton iteration is the exact step.
    let model = linear3(100.0, 1.0);
    let (h, factor) = (0.1, 1.0 / 3.0);
    let a = trace(&model, model.state(), h, 6, auto()).unwrap();
    let n = trace(&model, model.state(), h, 6, full()).unwrap();
    for (s, w) in [(&a, "auto"), (&n, "newton")] {
        for pair in s.windows(2) {
            let ratio = linear3_energy(&model, &pair[1]) / linear3_energy(&model, &pair[0]);
            assert!((ratio - factor).abs() < 1e-9, "{w}: {ratio}");
        }
    }
    let g = gap(a.last().unwrap(), n.last().unwrap());
    println!("linear attraction: auto vs newton after 6 steps {g:e}");
    assert!(g < 1e-12);
}

#[test]
fn linear_repulsion_default_equals_newton() {
    // fₐ = −k·d (k = 1, m = 1): d̈ = λ²d, λ² = 2, linear. (With `definite`, the one-step form
    // clamps the block's negative eigenvalues to 0, its matrix is M and its step symplectic
    // Euler: 0.167 from Newton at t = 1, which is why it is not the default.)
    let model = linear3(-1.0, 1.0);
    let (h, steps) = (0.1, 10);
    let a = trace(&model, model.state(), h, steps, auto()).unwrap();
    let n = trace(&model, model.state(), h, steps, full()).unwrap();
    // Exact: d(t) = cosh(λt) at t = 1.
    let exact = (2f64.sqrt()).cosh();
    let sep = |s: &ParticleState<3>| (s.positions()[1] - s.positions()[0]).x;
    println!(
        "repulsion t=1: exact {exact:.6}, newton {:.6}, auto {:.6}",
        sep(n.last().unwrap()),
        sep(a.last().unwrap())
    );
    let g = gap(a.last().unwrap(), n.last().unwrap());
    assert!(g < 1e-12, "auto vs newton {g:e}");
}

#[test]
fn constant_pair_force_with_zero_jacobian_is_exact_under_both() {
    // fₐ = F, f_b = −F, no stiffness: implicit Euler gives vₙ = n·h·F/m and
    // xₙ = x₀ + h²·F/m·n(n+1)/2 exactly (sum of the velocity updates).
    let mut model = linear3(0.0, 2.0);
    model.push = Vector3::new(1.0, -2.0, 0.5);
    let (h, steps) = (0.1, 10);
    for opts in [auto(), full()] {
        let s = trace(&model, model.state(), h, steps, opts).unwrap();
        let last = s.last().unwrap();
        let n = steps as f64;
        let expect_v = model.push * (n * h / 2.0);
        let expect_x = model.x[0] + model.push * (h * h / 2.0 * n * (n + 1.0) / 2.0);
        assert!((last.velocities()[0] - expect_v).norm() < 1e-12);
        assert!((last.positions()[0] - expect_x).norm() < 1e-12);
    }
}

#[test]
fn softened_gravity_orbit_energy_never_grows() {
    // A conservative pair force whose radial stiffness is negative (G·m²·(ε² − 2r²)/(r²+ε²)^{5/2}
    // < 0 for r > ε/√2). Implicit Euler on an orbit loses energy (it spirals in); the default
    // must not gain energy (the one-step definite form gained 32.8 in one step and ejected the
    // binary). 3-D, ~2 orbits.
    let model = binary();
    let sep = |s: &ParticleState<3>| (s.positions()[1] - s.positions()[0]).norm();
    let mut gains = Vec::new();
    for h in [0.05, 0.2, 0.5] {
        let steps = (9.0 / h) as usize;
        let a = trace(&model, model.state(), h, steps, auto()).unwrap();
        let n = trace(&model, model.state(), h, steps, full()).unwrap();
        for (name, s) in [("auto", &a), ("newton", &n)] {
            let mut worst = (0.0f64, 0usize);
            for (k, pair) in s.windows(2).enumerate() {
                let gain = gravity_energy(&model, &pair[1]) - gravity_energy(&model, &pair[0]);
                if gain > worst.0 {
                    worst = (gain, k + 1);
                }
            }
            let checkpoints: Vec<String> = (0..=4)
                .map(|q| {
                    let k = q * steps / 4;
                    format!(
                        "t={:.2} r={:.3} E={:.3}",
                        k as f64 * h,
                        sep(&s[k]),
                        gravity_energy(&model, &s[k])
                    )
                })
                .collect();
            println!(
                "gravity h={h} {name}: worst step gain {:e} at step {}; {}",
                worst.0,
                worst.1,
                checkpoints.join(", ")
            );
            if name == "auto" {
                gains.push((h, worst.0));
            }
        }
    }
    for (h, gain) in gains {
        assert!(gain <= 1e-12, "h = {h}: auto gained {gain:e}");
    }
}

#[test]
fn magnetic_force_particle_only_model_does_not_gain_energy() {
    // f = q·v × B does no work. Implicit Euler on v̇ = ω·J·v (ω = qB/m) divides v by 1 − iωh:
    // |v|² times 1/(1 + ω²h²) per step (ImplicitEuler's rustdoc). qB = 10, m = 1, h = 0.1:
    // factor 1/2 per step. (The one-step definite form projects ∂f/∂v onto its symmetric part,
    // zero here: its step is explicit Euler, |v|² times 1 + ω²h² = 2 per step.)
    let model = Charges {
        x: vec![Vector2::zeros(), Vector2::new(1.0, 0.0)],
        v: vec![Vector2::new(1.0, 0.0), Vector2::new(0.0, 2.0)],
        m: vec![1.0; 2],
        qb: 10.0,
        trap: 0.0,
    };
    let n = trace(&model, model.state(), 0.1, 10, full()).unwrap();
    for pair in n.windows(2) {
        let ratio = kinetic(&pair[1], &model.m) / kinetic(&pair[0], &model.m);
        assert!((ratio - 0.5).abs() < 1e-9, "newton {ratio}");
    }
    let a = trace(&model, model.state(), 0.1, 10, auto()).unwrap();
    let ratios: Vec<f64> = a
        .windows(2)
        .map(|p| kinetic(&p[1], &model.m) / kinetic(&p[0], &model.m))
        .collect();
    println!("magnetic: auto energy ratio per step {ratios:?}");
    for r in ratios {
        assert!(r <= 1.0, "auto gained energy: ×{r} per step");
    }
}

#[test]
fn damped_spring_pair_default_stays_near_newton_and_dissipates() {
    // 2-D rope with rest-length springs and an isotropic damper between the ends of each link:
    // nonlinear; the default must not gain energy (the damper only removes it). Released horizontal with an initial velocity kick on the tip, no gravity.
    let mut model = rope(10, 1e3, 0.05);
    model.v[9] = Vector2::new(0.0, 3.0);
    let (h, steps) = (1.0 / 60.0, 120);
    let a = trace(&model, model.state(), h, steps, auto()).unwrap();
    let n = trace(&model, model.state(), h, steps, full()).unwrap();
    let first = |s: &[ParticleState<2>]| -> Vec<String> {
        s.iter()
            .take(6)
            .map(|p| format!("{:.4}", spring_energy(&model, p)))
            .collect()
    };
    println!(
        "damped rope energies, first steps: auto {:?}, newton {:?}",
        first(&a),
        first(&n)
    );
    println!(
        "damped rope: E0 {:.5}, end auto {:.3e}, newton {:.3e}, max position gap {:.3e} m",
        spring_energy(&model, &a[0]),
        spring_energy(&model, a.last().unwrap()),
        spring_energy(&model, n.last().unwrap()),
        gap(a.last().unwrap(), n.last().unwrap())
    );
    for (s, w) in [(&n, "newton"), (&a, "auto")] {
        for pair in s.windows(2) {
            let (e0, e1) = (
                spring_energy(&model, &pair[0]),
                spring_energy(&model, &pair[1]),
            );
            assert!(e1 <= e0 + 1e-12 * e0.max(1.0), "{w}: {e0} -> {e1}");
        }
    }
}

#[test]
fn undamped_stiff_rope_default_never_gains_energy() {
    // The whipping-rope regime (k = 1e4, m = 5 g, ω·h ≈ 47), without damping.
    let mut model = rope(20, 1e4, 0.0);
    model.v[19] = Vector2::new(0.0, 5.0);
    let a = trace(&model, model.state(), 1.0 / 60.0, 240, auto()).unwrap();
    let n = trace(&model, model.state(), 1.0 / 60.0, 240, full()).unwrap();
    let first = |s: &[ParticleState<2>]| -> Vec<String> {
        s.iter()
            .take(6)
            .map(|p| format!("{:.4}", spring_energy(&model, p)))
            .collect()
    };
    let mut nworst = 0.0f64;
    for pair in n.windows(2) {
        nworst = nworst.max(spring_energy(&model, &pair[1]) - spring_energy(&model, &pair[0]));
    }
    println!(
        "stiff rope energies, first steps: auto {:?}, newton {:?}; newton worst gain {nworst:e}",
        first(&a),
        first(&n)
    );
    let mut worst = 0.0f64;
    for pair in a.windows(2) {
        worst = worst.max(spring_energy(&model, &pair[1]) - spring_energy(&model, &pair[0]));
    }
    println!(
        "stiff rope: E0 {:.4}, end {:.4e}, worst gain {worst:e}",
        spring_energy(&model, &a[0]),
        spring_energy(&model, a.last().unwrap())
    );
    assert!(worst <= 1e-12, "gained {worst:e}");
}

/// Why the default is not the one-step Baraff–Witkin form: on the same kicked rope it gains
/// energy in its first step, 0.0625 J → 11.2 J (the guide's particles chapter), where full
/// Newton loses some (0.0445 J): it linearizes once a step, and a link that turns through a
/// large angle in that step is not the link it linearized.
#[test]
fn the_one_step_form_gains_energy_on_a_kicked_rope() {
    let mut model = rope(20, 1e4, 0.0);
    model.v[19] = Vector2::new(0.0, 5.0);
    let e0 = spring_energy(&model, &model.state());
    let one = trace(&model, model.state(), 1.0 / 60.0, 1, by_hand()).unwrap();
    let newton = trace(&model, model.state(), 1.0 / 60.0, 1, full()).unwrap();
    let (e_one, e_newton) = (
        spring_energy(&model, &one[1]),
        spring_energy(&model, &newton[1]),
    );
    eprintln!(
        "kicked rope, one step: {e0:.4} J → Baraff–Witkin {e_one:.4} J, Newton {e_newton:.4} J"
    );
    assert!(
        e_newton < e0 && e_one > 10.0 * e0,
        "{e0} {e_one} {e_newton}"
    );
}

// ---------------------------------------------------------------------------------------------
// 2. Extreme inputs.

/// Both solves at (k, m, h) for 5 steps: their largest error against implicit Euler in closed
/// form, relative to the largest |d| or |w| of the closed form along the way. The separation d and its rate w
/// obey d̈ = −ω²d, ω² = 2k/m; one implicit Euler step is d' = (d + h·w)/(1 + ω²h²),
/// w' = (w − h·ω²·d)/(1 + ω²h²) (solve the 2×2 system); the centre of mass stays at rest.
fn linear_case(k: f64, m: f64, h: f64) -> [f64; 2] {
    let model = linear3(k, m);
    let (mut d, mut w) = (1.0f64, 0.0f64);
    let w2 = 2.0 * k / m;
    // Errors are measured against the largest |d| or |w| along the way (round-off of a
    // quantity of that size cannot be beaten).
    let mut scale = 1.0f64;
    for _ in 0..5 {
        let den = 1.0 + w2 * h * h;
        (d, w) = ((d + h * w) / den, (w - h * w2 * d) / den);
        scale = scale.max(d.abs()).max(w.abs());
    }
    [auto(), full()].map(|opts| match trace(&model, model.state(), h, 5, opts) {
        Ok(s) => {
            let last = s.last().unwrap();
            let (x, v) = (last.positions(), last.velocities());
            let (dd, ww) = (x[1].x - x[0].x, v[1].x - v[0].x);
            ((dd - d).abs().max((ww - w).abs()) / scale).max(
                if last.as_slice().iter().all(|c| c.is_finite()) {
                    0.0
                } else {
                    f64::NAN
                },
            )
        }
        Err(e) => {
            println!("k={k:e} m={m:e} h={h:e}: {e}");
            f64::NAN
        }
    })
}

#[test]
fn extreme_stiffness_mass_and_step() {
    let mut bad = Vec::new();
    for (k, m, h) in [
        (1e12, 1.0, 1.0 / 60.0),
        (1e-12, 1.0, 1.0 / 60.0),
        (100.0, 1e300, 1.0 / 60.0),
        (100.0, 1.0, 1e-9),
        (100.0, 1.0, 1e3),
    ] {
        let [ea, en] = linear_case(k, m, h);
        let model = linear3(k, m);
        if let (Ok(a), Ok(n)) = (
            trace(&model, model.state(), h, 5, auto()),
            trace(&model, model.state(), h, 5, full()),
        ) {
            println!(
                "  auto vs newton gap {:e}",
                gap(a.last().unwrap(), n.last().unwrap())
            );
        }
        println!(
            "linear k={k:e} m={m:e} h={h:e}: relative error vs closed form: auto {ea:e}, newton {en:e}"
        );
        if !(ea <= 1e-10 && en <= 1e-10) {
            bad.push((k, m, h, ea, en));
        }
    }
    assert!(bad.is_empty(), "{bad:?}");
    // A mass of 1e-300 beside k = 100 (k/m = 1e302): the model's values are finite but the
    // solve overflows; the error says so instead of blaming the model.
    let model = linear3(100.0, 1e-300);
    let error = trace(&model, model.state(), 1.0 / 60.0, 5, full()).unwrap_err();
    assert!(
        matches!(
            error,
            odyn::Error::NewtonDidNotConverge {
                cause: odyn::NewtonFailure::UpdateNotFinite,
                ..
            }
        ),
        "{error}"
    );
}

#[test]
fn extreme_step_on_a_nonlinear_cloth() {
    // dt = 1e3 s and 1e-9 s on a 4×4 falling cloth: the default must stay finite.
    let cloth = Sheet::falling(4).build().0;
    for h in [1e3, 1e-9] {
        let a = trace(&cloth, cloth.state(), h, 3, auto());
        let n = trace(&cloth, cloth.state(), h, 3, full());
        let show = |r: &odyn::Result<Vec<ParticleState<3>>>| match r {
            Ok(s) => format!(
                "ok, finite {}",
                s.last().unwrap().as_slice().iter().all(|c| c.is_finite())
            ),
            Err(e) => format!("Err({e})"),
        };
        println!("cloth h={h:e}: auto {}; newton {}", show(&a), show(&n));
        let a = a.unwrap();
        assert!(a.last().unwrap().as_slice().iter().all(|c| c.is_finite()));
    }
}

#[test]
fn non_finite_positions_are_a_typed_error() {
    for bad in [f64::NAN, f64::INFINITY] {
        let mut model = linear3(100.0, 1.0);
        model.x[1].y = bad;
        let run = model
            .simulate()
            .integrator(Method::ImplicitEuler)
            .steps(3)
            .run();
        let stepped = trace(&model, model.state(), 0.01, 3, auto());
        println!(
            "position {bad}: simulate -> {:?}; stepper -> {:?}",
            run.as_ref()
                .map(|r| r.samples.last().unwrap().state.clone())
                .map_err(|e| e.to_string()),
            stepped
                .as_ref()
                .map(|s| s.last().unwrap().clone())
                .map_err(|e| e.to_string())
        );
        assert!(run.is_err(), "{bad}: simulate accepted it");
        assert!(stepped.is_err(), "{bad}: stepper accepted it");
    }
}

#[test]
fn non_finite_parameter_is_a_typed_error() {
    let mut model = linear3(f64::NAN, 1.0);
    model.k = f64::NAN;
    let r = model
        .simulate()
        .integrator(Method::ImplicitEuler)
        .steps(3)
        .run();
    println!(
        "k = NaN: {:?}",
        r.as_ref().map(|_| ()).map_err(|e| e.to_string())
    );
    assert!(r.is_err());
}

#[test]
fn topology_edge_cases() {
    let bad = |model: &Linear3| match model
        .simulate()
        .integrator(Method::ImplicitEuler)
        .steps(2)
        .run()
    {
        Err(Error::BadModel { what, reason, .. }) => format!("BadModel {what}: {reason}"),
        Err(e) => panic!("other error {e}"),
        Ok(_) => panic!("accepted"),
    };
    let mut pin = linear3(100.0, 1.0);
    pin.pins = vec![2];
    println!("pinned out of range: {}", bad(&pin));
    let mut selfy = linear3(100.0, 1.0);
    selfy.links = vec![[1, 1]];
    println!("self link: {}", bad(&selfy));
    let mut far = linear3(100.0, 1.0);
    far.links = vec![[0, usize::MAX]];
    println!("link to usize::MAX: {}", bad(&far));

    // Every particle pinned: nothing moves.
    let mut all = linear3(100.0, 1.0);
    all.pins = vec![0, 1];
    let s = trace(&all, all.state(), 0.1, 3, auto()).unwrap();
    assert_eq!(bits(&s[0]), bits(s.last().unwrap()));
    // Duplicate pins are accepted and mean the same.
    all.pins = vec![0, 1, 1, 0];
    let s = trace(&all, all.state(), 0.1, 3, auto()).unwrap();
    assert_eq!(bits(&s[0]), bits(s.last().unwrap()));

    // One particle, zero links, a constant particle force: Charges with a trap only: linear,
    // auto = newton.
    let one = Charges {
        x: vec![Vector2::new(1.0, 0.0)],
        v: vec![Vector2::zeros()],
        m: vec![1.0],
        qb: 0.0,
        trap: 4.0,
    };
    let a = trace(&one, one.state(), 0.1, 5, auto()).unwrap();
    let n = trace(&one, one.state(), 0.1, 5, full()).unwrap();
    assert!(gap(a.last().unwrap(), n.last().unwrap()) < 1e-14);
    // Zero links on a pair model: free flight, x = x₀ + n·h·v₀.
    let mut free = linear3(100.0, 1.0);
    free.links.clear();
    free.v[1] = Vector3::new(0.0, 1.0, 0.0);
    let s = trace(&free, free.state(), 0.1, 10, auto()).unwrap();
    assert!((s.last().unwrap().positions()[1] - Vector3::new(1.0, 1.0, 0.0)).norm() < 1e-14);
    // Zero particles.
    let mut empty = linear3(100.0, 1.0);
    empty.x.clear();
    empty.v.clear();
    empty.m.clear();
    empty.links.clear();
    let r = trace(&empty, empty.state(), 0.1, 2, auto());
    println!(
        "zero particles: {:?}",
        r.as_ref().map(|s| s.len()).map_err(|e| e.to_string())
    );
}

#[test]
fn duplicate_links_equal_one_link_of_twice_the_stiffness() {
    // Forces add: two identical springs of k are one of 2k (Hooke), Jacobians included.
    let mut two = rope(6, 1e3, 0.0);
    two.v[5] = Vector2::new(0.0, 2.0);
    let mut doubled = two.clone();
    let extra = two.springs.clone();
    two.springs.extend(extra);
    for s in &mut doubled.springs {
        s.stiffness *= 2.0;
    }
    let a = trace(&two, two.state(), 1.0 / 60.0, 60, auto()).unwrap();
    let b = trace(&doubled, doubled.state(), 1.0 / 60.0, 60, auto()).unwrap();
    let g = gap(a.last().unwrap(), b.last().unwrap());
    println!("duplicate links vs 2k: {g:e}");
    assert!(g < 1e-9);
}

#[test]
fn zero_length_link_and_coincident_spring_ends() {
    // A [usize; 2] link whose ends coincide: the linear pull is 0 with stiffness k, fine.
    let mut model = linear3(100.0, 1.0);
    model.x[1] = model.x[0];
    model.v[1] = Vector3::new(1.0, 0.0, 0.0);
    let a = trace(&model, model.state(), 0.1, 5, auto()).unwrap();
    let n = trace(&model, model.state(), 0.1, 5, full()).unwrap();
    assert!(gap(a.last().unwrap(), n.last().unwrap()) < 1e-12);
    // A Spring (rest 0.05) whose two ends start at the same point: d/|d| is 0/0. Expect a typed
    // error, not a silent NaN state.
    let mut r = rope(3, 1e3, 0.0);
    r.x[2] = r.x[1];
    let out = trace(&r, r.state(), 0.01, 2, auto());
    let run = r
        .simulate()
        .integrator(Method::ImplicitEuler)
        .steps(2)
        .run();
    println!(
        "coincident spring ends: stepper {:?}; simulate {:?}",
        out.as_ref()
            .map(|s| s.last().unwrap().clone())
            .map_err(|e| e.to_string()),
        run.as_ref().map(|_| ()).map_err(|e| e.to_string())
    );
    assert!(out.is_err() && run.is_err());
}

// ---------------------------------------------------------------------------------------------
// 3. The default against the same options set by hand.

/// The default (`ParticleSolve::Auto`) is full Newton: bit for bit `ParticleSolve::Newton`
/// with the same options, on a falling 6×6 cloth for 30 steps.
#[test]
fn the_default_is_full_newton_bit_for_bit() {
    let cloth = Sheet::falling(6).build().0;
    let h = 1.0 / 60.0;
    let reference = trace(&cloth, cloth.state(), h, 30, auto()).unwrap();
    let s = trace(&cloth, cloth.state(), h, 30, full()).unwrap();
    for (k, (p, q)) in s.iter().zip(&reference).enumerate() {
        assert_eq!(bits(p), bits(q), "step {k}");
    }
}

#[test]
fn full_newton_converges_to_tol_on_a_small_stiff_cloth() {
    // ParticleSolve::Newton with linearized false: each step's iterate satisfies the implicit
    // Euler equations y − yₙ − h·f(y) = 0 to Newton's tolerance (the last update ≤ tol·(1+|y|),
    // so the residual is at most about ‖I − hJ‖·tol).
    let cloth = Sheet::falling(6).build().0;
    let h = 1.0 / 60.0;
    let tight = NewtonOptions {
        tol: 1e-10,
        ..full()
    };
    // Only steps Newton did not halve: a halved step is two implicit Euler steps of h/2.
    let residual = |opts: NewtonOptions| {
        let mut stepper =
            Stepper::<_, ImplicitEuler<_>>::with_newton(&cloth, cloth.state(), 0.0, h, &opts)
                .unwrap();
        let (mut worst, mut halved) = (0.0f64, 0);
        let mut f = cloth.state();
        for _ in 0..30 {
            let (y0, rejected) = (stepper.state().clone(), stepper.stats().rejected);
            stepper.step().unwrap();
            if stepper.stats().rejected > rejected {
                halved += 1;
                continue;
            }
            let y1 = stepper.state();
            cloth.derivative(h, y1, &mut f);
            for ((a, b), fi) in y1.as_slice().iter().zip(y0.as_slice()).zip(f.as_slice()) {
                worst = worst.max((a - b - h * fi).abs());
            }
        }
        (worst, halved, stepper.stats())
    };
    let ((rn, hn, sn), (ra, ha, _)) = (residual(tight), residual(auto()));
    println!(
        "stiff cloth max implicit-Euler residual on unhalved steps: newton {rn:e} ({hn} of 30 \
         halved; {} Jacobians, {} rejected), auto {ra:e} ({ha} halved)",
        sn.jacobian_evaluations, sn.rejected
    );
    // Bound: |Δ| ≤ 1e-10·(1 + |y|) with ‖I − hJ‖ ≲ 1 + 4h·k/m ≈ 5e4 (k = 1e4, m = 0.5/36 kg).
    assert!(rn < 1e-4, "{rn:e}");
}

// ---------------------------------------------------------------------------------------------
// 4. Options given beside the default.

/// Options given with `ParticleSolve::Auto` (linearized off, definite off, tol 1e-14, 100
/// iterations) are the run's: bit for bit the same options with `ParticleSolve::Newton`.
#[test]
fn options_given_beside_the_default_are_honoured() {
    let cloth = Sheet::falling(5).build().0;
    let h = 1.0 / 60.0;
    let asked = NewtonOptions {
        linearized: false,
        definite: false,
        tol: 1e-14,
        max_iterations: 100,
        ..NewtonOptions::default()
    };
    let a = trace(&cloth, cloth.state(), h, 20, asked).unwrap();
    let n = trace(
        &cloth,
        cloth.state(),
        h,
        20,
        NewtonOptions {
            particle_solve: ParticleSolve::Newton,
            ..asked
        },
    )
    .unwrap();
    assert_eq!(bits(a.last().unwrap()), bits(n.last().unwrap()));
}
