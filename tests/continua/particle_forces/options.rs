//! The default against the same options set by hand.

use super::*;

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
