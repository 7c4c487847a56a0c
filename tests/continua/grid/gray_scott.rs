//! Gray–Scott: two coupled fields on every boundary, conservation, every first-order method,
//! the explicit limit from Gershgorin's discs, and agreement with SciPy's solution.

use odyn::grid::{Boundary, Grid, GridState};
use odyn::stability::gershgorin_limit;
use odyn::{Method, Model, Simulate, State};

use super::{GrayScott, check_jacobian, gray_scott};

/// Two coupled fields on every boundary: the generated blocks, placed through the boundary
/// (periodic wrap, Neumann's reads folded onto the edge cell), match finite differences.
#[test]
fn two_field_jacobian_matches_finite_differences_on_every_boundary() {
    for boundary in [
        Boundary::Periodic,
        Boundary::Neumann,
        Boundary::Dirichlet(0.3),
    ] {
        check_jacobian(&gray_scott(5, boundary));
    }
}

/// Pure diffusion (F = k = 0 and no v) conserves the total of u on periodic and Neumann
/// (zero-flux) grids: the five-point fluxes cancel in pairs. Explicit Euler keeps the sum to
/// rounding over 1000 steps.
#[test]
fn diffusion_conserves_the_total_on_periodic_and_neumann_grids() {
    for boundary in [Boundary::Periodic, Boundary::Neumann] {
        let mut model = gray_scott(12, boundary);
        (model.feed, model.kill) = (0.0, 0.0);
        model.v.values_mut().fill(0.0);
        let total = |s: &GridState| s.field(0).iter().sum::<f64>();
        let start = total(&model.state());
        let trajectory = model.simulate().steps(1000).run().unwrap();
        let end = total(&trajectory.samples.last().unwrap().state);
        assert!(
            (end - start).abs() < 1e-11 * start,
            "{boundary:?}: total {start} became {end}"
        );
    }
}

/// Every integrator that needs only f (and J) runs on a field model: against a DOP853 reference
/// at rtol 1e-12 over t = 20, each converges at its order p: the error ratio between dt = 1 and
/// 1/2 gives p − 0.25 < measured < p + 1 (Tsit5 measures 5.9: its fifth-order error constant is
/// tuned small, so the sixth-order term still shows at these steps), and DOP853, whose error at dt = 1
/// is already near the reference's, agrees to 1e-9.
#[test]
fn every_first_order_method_runs_on_a_field_model() {
    let model = gray_scott(8, Boundary::Periodic);
    let reference = model
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-12, 1e-14)
        .duration(20.0)
        .run()
        .unwrap();
    let reference = reference.samples.last().unwrap().state.clone();
    let error = |method: Method, dt: f64| {
        let run = model
            .simulate()
            .integrator(method)
            .dt(dt)
            .duration(20.0)
            .run()
            .unwrap();
        let state = &run.samples.last().unwrap().state;
        crate::common::max_abs_difference(state.as_slice(), reference.as_slice())
    };
    for (method, order, dt) in [
        (Method::ExplicitEuler, 1.0, 1.0),
        (Method::ImplicitEuler, 1.0, 1.0),
        (Method::Rosenbrock23, 2.0, 1.0),
        (Method::Rk4, 4.0, 1.0),
        (Method::Tsit5, 5.0, 1.0),
        (Method::Rodas5P, 5.0, 1.0),
    ] {
        let measured = (error(method, dt) / error(method, dt / 2.0)).log2();
        assert!(
            measured > order - 0.25 && measured < order + 1.0,
            "{method:?}: order {measured}"
        );
    }
    let e = error(Method::Dop853, 1.0);
    assert!(e < 1e-9, "DOP853: {e}");
}

/// At the uniform background (u, v) = (1, 0) the Jacobian is circulant and the checkerboard
/// mode's eigenvalue −8D_u/dx² − F sits on a Gershgorin rim: explicit Euler's predicted limit
/// is 2/(8D_u/dx² + F) exactly (the example's check of the dx²/(4D_u), less F's share).
#[test]
fn gray_scott_explicit_limit_is_predicted_from_the_discs() {
    let mut model = gray_scott(16, Boundary::Periodic);
    // Pearson's cells, where diffusion sets the limit.
    model.dx = 2.5 / 256.0;
    model.u.values_mut().fill(1.0);
    model.v.values_mut().fill(0.0);
    let state = model.state();
    let predicted = gershgorin_limit(&model, 0.0, &state, Method::ExplicitEuler).unwrap();
    let theory = 2.0 / (8.0 * model.du / (model.dx * model.dx) + model.feed);
    assert!(
        (predicted / theory - 1.0).abs() < 1e-12,
        "{predicted} vs {theory}"
    );
    assert_eq!(
        gershgorin_limit(&model, 0.0, &state, Method::ImplicitEuler).unwrap(),
        f64::INFINITY
    );
}

/// odyn's Gray–Scott against SciPy's: "coral" (F = 0.0545, k = 0.062) on 64² cells from
/// Pearson's square without noise, to t = 500, DOP853 at rtol = atol = 1e-12, against
/// `scripts/scipy_gray_scott.py`'s reference (SciPy DOP853 at 1e-13, which its Radau at 1e-10
/// matches to 1.4e-11): the bench `gray_scott`'s `equal_accuracy` reference.
#[test]
fn gray_scott_matches_scipy() {
    let n = 64;
    let r = n * 10 / 256;
    let inside = |i: usize, j: usize| {
        (n / 2 - r..n / 2 + r).contains(&i) && (n / 2 - r..n / 2 + r).contains(&j)
    };
    let grid = |inner: f64, outer: f64| {
        Grid::from_fn(n, n, Boundary::Periodic, |i, j| {
            if inside(i, j) { inner } else { outer }
        })
        .unwrap()
    };
    let model = GrayScott {
        u: grid(0.5, 1.0),
        v: grid(0.25, 0.0),
        du: 2e-5,
        dv: 1e-5,
        feed: 0.0545,
        kill: 0.062,
        dx: 2.5 / n as f64,
    };
    let run = model
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-12, 1e-12)
        .duration(500.0)
        .record_every(u64::MAX)
        .run()
        .unwrap();
    let y = run.samples.last().unwrap().state.as_slice().to_vec();
    // scripts/scipy_gray_scott.py: (index, value) in odyn's layout (u then v, k = j·n + i).
    let probes = [
        (0, 1.0),
        (2080, 0.444875936730885),
        (2087, 0.9999873470631493),
        (6176, 0.250463872401409),
        (6183, 6.937624869473619e-09),
    ];
    for (k, expected) in probes {
        assert!(
            (y[k] - expected).abs() < 1e-9,
            "y[{k}] = {} vs SciPy {expected}",
            y[k]
        );
    }
    let mean = |s: &[f64]| s.iter().sum::<f64>() / s.len() as f64;
    assert!((mean(&y[..n * n]) - 9.969918721584972e-01).abs() < 1e-10);
    assert!((mean(&y[n * n..]) - 1.407236166694929e-03).abs() < 1e-10);
}
