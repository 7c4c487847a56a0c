//! Extreme stiffnesses, masses and steps; non-finite input and topology edge cases as typed
//! errors.

use super::*;

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
