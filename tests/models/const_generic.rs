//! Const-generic models (`struct Chain<const N: usize>`): the state type follows the
//! parameters; every method runs; explicit runs are bit for bit those of the same model written
//! for one `N` (the same arithmetic in the same order); the Jacobian — central differences of f,
//! since the macro does not lower code whose loops run to `N` — agrees with the concrete
//! model's exact one; and a first-order generic model decays as the theory of its discrete
//! Laplacian says.

use crate::common::{self, Rng};
use crate::shapes::{Chain, ChainState, three_bodies};

use odyn::prelude::*;
use odyn::{DenseMatrix, Jacobian, Method};

/// [`Chain`] for any number of masses: the same body with `N` for 4.
#[system]
#[derive(Clone, Copy)]
struct Links<const N: usize> {
    #[position]
    q: [Vector2<f64>; N],
    #[velocity]
    p: [Vector2<f64>; N],
    k: f64,
}

#[system]
impl<const N: usize> Links<N> {
    fn acceleration(&self) -> [Vector2<f64>; N] {
        let mut a = [Vector2::new(0.0, -9.81); N];
        let mut previous = Vector2::<f64>::zeros();
        for i in 0..N {
            let d = self.q[i] - previous;
            let length = d.norm();
            let f = d * (self.k * (length - 1.0) / length);
            a[i] -= f;
            if i > 0 {
                a[i - 1] += f;
            }
            previous = self.q[i];
        }
        a
    }

    /// Kinetic, gravitational (g = 9.81, unit masses) and spring energy.
    fn energy(&self) -> f64 {
        let mut e = 0.0;
        let mut previous = Vector2::<f64>::zeros();
        for i in 0..N {
            let stretch = (self.q[i] - previous).norm() - 1.0;
            e += 0.5 * self.p[i].norm_squared() + 9.81 * self.q[i].y;
            e += 0.5 * self.k * stretch * stretch;
            previous = self.q[i];
        }
        e
    }
}

fn links<const N: usize>() -> Links<N> {
    Links {
        q: std::array::from_fn(|i| Vector2::new(1.1 * (i + 1) as f64, 0.0)),
        p: [Vector2::zeros(); N],
        k: 50.0,
    }
}

fn chain() -> Chain {
    Chain {
        q: std::array::from_fn(|i| Vector2::new(1.1 * (i + 1) as f64, 0.0)),
        p: [Vector2::zeros(); 4],
        k: 50.0,
    }
}

/// [`crate::shapes::ThreeBodies`] for any number of bodies, its masses a parameter array of the same length.
#[system]
#[derive(Clone, Copy, Debug)]
struct Bodies<const N: usize> {
    #[position]
    r: [Vector3<f64>; N],
    #[velocity]
    v: [Vector3<f64>; N],
    m: [f64; N],
    g: f64,
}

#[system]
impl<const N: usize> Bodies<N> {
    fn acceleration(&self) -> [Vector3<f64>; N] {
        let mut a = [Vector3::<f64>::zeros(); N];
        for i in 0..N {
            for j in (i + 1)..N {
                let d = self.r[j] - self.r[i];
                let r2 = d.x * d.x + d.y * d.y + d.z * d.z;
                let s = self.g / (r2 * r2.sqrt());
                a[i] += d * (self.m[j] * s);
                a[j] -= d * (self.m[i] * s);
            }
        }
        a
    }
}

/// Heat conduction along a rod of `N` cells with both ends held at zero, u′ = κ·Δu (the
/// three-point Laplacian, unit spacing): first-order, its state a `[f64; N]`.
#[system]
#[derive(Clone, Copy, Debug)]
struct Rod<const N: usize> {
    #[state]
    u: [f64; N],
    kappa: f64,
}

#[system]
#[allow(
    clippy::needless_range_loop,
    reason = "a stencil reads its neighbours by index"
)]
impl<const N: usize> Rod<N> {
    fn derivative(&self) -> RodState<N> {
        let mut du = [0.0; N];
        for i in 0..N {
            let left = if i > 0 { self.u[i - 1] } else { 0.0 };
            let right = if i + 1 < N { self.u[i + 1] } else { 0.0 };
            du[i] = self.kappa * (left - 2.0 * self.u[i] + right);
        }
        RodState { u: du }
    }
}

/// Two const parameters, rows of a row-major `R`×`C` grid: only the layout is under test.
#[system(jacobian = false)]
#[derive(Clone, Copy, Debug)]
struct Sheet<const R: usize, const C: usize> {
    #[state]
    u: [[f64; C]; R],
    #[state]
    w: f64,
}

#[system]
impl<const R: usize, const C: usize> Sheet<R, C> {
    fn derivative(&self) -> SheetState<R, C> {
        SheetState {
            u: [[-self.w; C]; R],
            w: 0.0,
        }
    }
}

#[test]
fn the_state_type_follows_the_parameters() {
    let generic = links::<4>().state();
    let concrete = chain().state();
    assert_eq!(LinksState::<4>::LEN, 16);
    assert_eq!(LinksState::<7>::LEN, 28);
    assert_eq!(generic.as_slice(), concrete.as_slice());
    for i in 0..=16 {
        assert_eq!(generic.component_name(i), concrete.component_name(i));
    }
    assert_eq!(generic.component_name(9), "p[0][1]");

    let sheet = Sheet::<2, 3> {
        u: [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]],
        w: 7.0,
    }
    .state();
    assert_eq!(SheetState::<2, 3>::LEN, 7);
    assert_eq!(sheet.as_slice(), &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]);
    assert_eq!(sheet.component_name(5), "u[1][2]");
    assert_eq!(sheet.component_name(6), "w");
    assert_eq!(sheet.component_name(7), "#7");
    // The state's arithmetic, component by component.
    let twice = sheet + sheet;
    assert_eq!(twice.as_slice()[6], 14.0);
    assert_eq!(
        (2.0 * sheet - twice).as_slice(),
        SheetState::<2, 3>::zeros().as_slice()
    );
    assert_eq!((-sheet).u[1][0], -4.0);
    const { assert!(!<Sheet<2, 3> as Model>::Jacobian::AVAILABLE) };
    let run = Sheet::<2, 3> {
        u: [[0.0; 3]; 2],
        w: 1.0,
    }
    .simulate()
    .dt(0.25)
    .steps(4)
    .run()
    .unwrap();
    // u′ = −w with w constant: u(1) = −1 exactly, for RK4 too.
    assert_eq!(run.last().state.u, [[-1.0; 3]; 2]);
}

/// The samples and the final state of `model` under `method`: a fixed step of `dt` for
/// `steps` steps (adaptive methods start at `dt`).
fn last<M: Model>(model: &M, method: Method, dt: f64, steps: u64) -> (usize, Vec<f64>) {
    let run = model
        .simulate()
        .integrator(method)
        .dt(dt)
        .steps(steps)
        .run()
        .unwrap_or_else(|e| panic!("{} under {method}: {e}", M::NAME));
    (run.samples.len(), run.last().state.as_slice().to_vec())
}

/// Every method without a Jacobian gives the generic chain the concrete chain's bits: the same
/// arithmetic in the same order (the concrete model's loops unrolled, the generic one's not).
#[test]
fn explicit_runs_match_the_concrete_model_bit_for_bit() {
    let (generic, concrete) = (links::<4>(), chain());
    for method in Method::ALL.into_iter().filter(|m| !m.info().needs_jacobian) {
        assert_eq!(
            last(&generic, method, 1e-3, 300),
            last(&concrete, method, 1e-3, 300),
            "{method}"
        );
    }
    // Energy is the user's function, as written: four springs stretched by 0.1 at rest.
    let e = Model::energy(&generic, &generic.state()).unwrap();
    assert!((e - 4.0 * 0.5 * 50.0 * 0.1 * 0.1).abs() < 1e-12, "{e}");

    let three = three_bodies();
    let bodies = Bodies::<3> {
        r: three.r,
        v: three.v,
        m: three.m,
        g: three.g,
    };
    for method in [Method::Dop853, Method::Rk4, Method::Yoshida4] {
        assert_eq!(
            last(&bodies, method, 10.0, 400),
            last(&three, method, 10.0, 400),
            "{method}"
        );
    }
}

/// The Jacobian is central differences of f (`EXACT` false, no pattern), within what they
/// resolve of the concrete model's exact one at random states.
#[test]
fn the_jacobian_is_differences_of_f() {
    const { assert!(!<Links<4> as Jacobian>::EXACT) };
    assert!(<Links<4> as Jacobian>::NONZEROS.is_empty());
    let (generic, concrete) = (links::<4>(), chain());
    let mut rng = Rng(0x5DEE_CE66_D1CE_4E5B);
    for _ in 0..20 {
        let q: [Vector2<f64>; 4] = std::array::from_fn(|i| {
            Vector2::new(
                1.1 * (i + 1) as f64 + rng.uniform(-0.3, 0.3),
                rng.uniform(-1.0, 1.0),
            )
        });
        let p: [Vector2<f64>; 4] =
            std::array::from_fn(|_| Vector2::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)));
        let (y, exact_y) = (LinksState { q, p }, ChainState { q, p });
        let mut jacobian = generic.jacobian_matrix(&y);
        generic.jacobian(0.0, &y, &mut jacobian);
        let mut exact = concrete.jacobian_matrix(&exact_y);
        concrete.jacobian(0.0, &exact_y, &mut exact);
        assert_eq!(jacobian.dim(), 16);
        let scale = exact.abs().max();
        for row in 0..16 {
            for column in 0..16 {
                let (d, e) = (jacobian.entry(row, column), exact[(row, column)]);
                // Central differences with h = ε^⅓·max(1, |y|): ~1e-10 relative on this f.
                assert!(
                    (d - e).abs() <= 1e-7 * scale,
                    "({row}, {column}): {d} against {e}"
                );
            }
        }
    }
    common::check(&generic, 0.0, 5, |r: &mut Rng| LinksState {
        q: std::array::from_fn(|i| Vector2::new(1.1 * (i + 1) as f64, r.uniform(-0.5, 0.5))),
        p: [Vector2::zeros(); 4],
    });
}

/// The final state of `model` at t = 1 under `method` at rtol = atol = `tolerance`.
fn tight<M: Model>(model: &M, method: Method, tolerance: f64) -> Vec<f64> {
    let run = model
        .simulate()
        .integrator(method)
        .tolerances(tolerance, tolerance)
        .dt(1e-3)
        .duration(1.0)
        .run()
        .unwrap_or_else(|e| panic!("{} under {method}: {e}", M::NAME));
    run.last().state.as_slice().to_vec()
}

/// The implicit methods run the generic chain on its difference Jacobian and land where they
/// land on the concrete chain's exact one.
#[test]
fn implicit_methods_agree_with_the_exact_jacobian() {
    let (generic, concrete) = (links::<4>(), chain());
    for method in [
        Method::ImplicitEuler,
        Method::Rosenbrock23,
        Method::Rodas5P,
        Method::Bdf,
    ] {
        // Newton methods only iterate with J; Rosenbrock methods build it into their stages,
        // whose results move by about J's error, ~1e-10 relative (measured: 1e-14 or less).
        let apart = common::max_abs_difference(
            &tight(&generic, method, 1e-8),
            &tight(&concrete, method, 1e-8),
        );
        assert!(apart < 1e-10, "{method}: {apart:e}");
    }
}

/// The rod's lowest mode, uᵢ = sin(π(i+1)/(N+1)), is an eigenvector of the Dirichlet
/// three-point Laplacian with eigenvalue −4·sin²(π/(2(N+1))) (LeVeque, *Finite Difference
/// Methods for ODEs and PDEs*, 2007, §2.10.1, at unit spacing): it decays as exp(−4κ·sin²(π/(2(N+1)))·t). At N = 50
/// (a heap `FaerDense` Jacobian) and κ = 100 the fastest mode's rate is ~400: stiff.
#[test]
fn a_first_order_generic_model_decays_as_theory_says() {
    const N: usize = 50;
    let kappa = 100.0;
    let mode: [f64; N] =
        std::array::from_fn(|i| (std::f64::consts::PI * (i + 1) as f64 / (N + 1) as f64).sin());
    let rod = Rod::<N> { u: mode, kappa };
    let rate = 4.0
        * kappa
        * (std::f64::consts::PI / (2.0 * (N + 1) as f64))
            .sin()
            .powi(2);
    let t = 2.0;
    for method in [Method::Rodas5P, Method::Bdf] {
        let run = rod
            .simulate()
            .integrator(method)
            .tolerances(1e-9, 1e-12)
            .duration(t)
            .run()
            .unwrap_or_else(|e| panic!("{method}: {e}"));
        let decay = (-rate * t).exp();
        let error = run
            .last()
            .state
            .u
            .iter()
            .zip(&mode)
            .fold(0.0f64, |m, (u, s)| m.max((u - s * decay).abs()));
        // At rtol 1e-9 (measured: Rodas5P 5.9e-13, BDF 1.6e-9).
        assert!(error < 1e-8, "{method}: {error:e}");
    }
}
