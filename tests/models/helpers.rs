//! Helper functions marked `#[odyn::function]`: the Jacobians the macro derives by inlining them
//! against central differences, ∂f/∂t through a helper, and runs of a model with helpers against
//! the same model with the helpers inlined by hand.
//!
//! Tolerance: `common::check` compares with central differences at h = 1e-6·(1 + |yⱼ|): the
//! truncation error is O(h²·|f‴|) ≈ 1e-12 and the rounding error O(ε·|f|/h) ≈ 1e-10 relative to
//! the row's scale for these smooth, O(1)–O(100) forces, so 1e-6 relative fails on any wrong
//! derivative (a missing term is O(1)) and never on a right one. The random states stay off the
//! measure-zero kinks of `abs` and of the `if`s, where a difference quotient straddles two arms.

use crate::common;

use common::check;
use odyn::nalgebra::{Vector2, Vector3};
use odyn::particles::Spring;
use odyn::prelude::*;

/// A Duffing oscillator with quadratic drag, m·ẍ = −k·x − c·x³ − b·v·|v|, written with nested
/// helpers: `total` calls `restoring` (a method reading parameters) and `drag` (an associated
/// function given a parameter and the state).
#[system(integrator = Rodas5P)]
#[derive(Clone, Copy, Debug)]
struct Duffing {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    k: f64,
    c: f64,
    b: f64,
    m: f64,
}

#[system]
impl Duffing {
    fn acceleration(&self) -> f64 {
        self.total(self.x, self.v) / self.m
    }

    fn energy(&self) -> f64 {
        0.5 * self.m * self.v * self.v
            + 0.5 * self.k * self.x.powi(2)
            + 0.25 * self.c * self.x.powi(4)
    }

    #[odyn::function]
    fn total(&self, x: f64, v: f64) -> f64 {
        self.restoring(x) + Self::drag(self.b, v)
    }

    #[odyn::function]
    fn restoring(&self, x: f64) -> f64 {
        -self.k * x - self.c * x.powi(3)
    }

    #[odyn::function]
    fn drag(b: f64, v: f64) -> f64 {
        -b * v * v.abs()
    }
}

/// [`Duffing`] with its helpers inlined by hand, operation for operation.
#[system(integrator = Rodas5P)]
#[derive(Clone, Copy, Debug)]
struct DuffingInline {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    k: f64,
    c: f64,
    b: f64,
    m: f64,
}

#[system]
impl DuffingInline {
    fn acceleration(&self) -> f64 {
        (-self.k * self.x - self.c * self.x.powi(3) + -self.b * self.v * self.v.abs()) / self.m
    }
}

const DUFFING: Duffing = Duffing {
    x: 1.2,
    v: 0.0,
    k: 1.0,
    c: 5.0,
    b: 0.3,
    m: 0.5,
};

#[test]
fn nested_helpers_reading_parameters_have_exact_jacobians() {
    check(&DUFFING, 0.0, 200, |r| DuffingState {
        x: r.uniform(-3.0, 3.0),
        // Off the kink of |v| at 0.
        v: if r.uniform(0.0, 1.0) < 0.5 {
            r.uniform(-3.0, -0.01)
        } else {
            r.uniform(0.01, 3.0)
        },
    });
    // By hand: ∂a/∂x = (−k − 3c·x²)/m, ∂a/∂v = −2b·|v|/m.
    let y = DuffingState { x: 0.5, v: -2.0 };
    let mut j = DUFFING.jacobian_matrix(&y);
    DUFFING.jacobian(0.0, &y, &mut j);
    assert_eq!(j[(1, 0)], (-1.0 - 3.0 * 5.0 * 0.25) / 0.5);
    assert_eq!(j[(1, 1)], -2.0 * 0.3 * 2.0 / 0.5);
    assert_eq!(Duffing::NONZEROS, DuffingInline::NONZEROS);
}

#[test]
fn a_model_with_helpers_runs_as_the_same_model_inlined_by_hand() {
    // Bit for bit: the force calls the helpers, whose arithmetic is the hand-inlined force's
    // operation for operation (Rust neither reassociates nor contracts f64 arithmetic), and the
    // Jacobian code is generated from the same expression graph, so Rodas5P takes the same steps
    // on the same numbers.
    let inline = DuffingInline {
        x: DUFFING.x,
        v: DUFFING.v,
        k: DUFFING.k,
        c: DUFFING.c,
        b: DUFFING.b,
        m: DUFFING.m,
    };
    let with = DUFFING
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-8, 1e-10)
        .duration(20.0)
        .run()
        .unwrap();
    let by_hand = inline
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-8, 1e-10)
        .duration(20.0)
        .run()
        .unwrap();
    assert_eq!(with.samples.len(), by_hand.samples.len());
    assert!(with.samples.len() > 50, "{} samples", with.samples.len());
    for (a, b) in with.samples.iter().zip(&by_hand.samples) {
        assert_eq!(a.t.to_bits(), b.t.to_bits());
        assert_eq!(a.state.x.to_bits(), b.state.x.to_bits(), "x at t = {}", a.t);
        assert_eq!(a.state.v.to_bits(), b.state.v.to_bits(), "v at t = {}", a.t);
    }
    // Drag only takes energy away.
    let energy = |s: &DuffingState| {
        Duffing {
            x: s.x,
            v: s.v,
            ..DUFFING
        }
        .energy()
    };
    assert!(energy(&with.last().state) < energy(&with.first().state));
}

/// A first-order model whose helpers branch on their argument (`if` on the state inside a
/// helper), return a tuple, take and return vectors, and read the time.
#[system(integrator = Rodas5P)]
#[derive(Clone, Copy, Debug)]
struct Helped {
    #[state]
    p: f64,
    #[state]
    q: f64,
    #[state]
    r: Vector2<f64>,
    a: f64,
    gm: f64,
    scale: f64,
    k: f64,
    soft: bool,
}

#[system]
impl Helped {
    fn derivative(&self, t: f64) -> HelpedState {
        // A local the helper's own `k` must not shadow: `k.floor()` is state-free code odyn
        // leaves to the prologue, which reads `k` by name after the helper's code ran.
        let k = self.a + 0.5;
        let (radius, angle) = Self::polar(self.p, self.q);
        let soft = self.ramp(self.p - self.q);
        let kk = k.floor();
        HelpedState {
            p: soft - kk * self.p + self.drive(t) * angle.cos(),
            q: radius.sin() - self.q * Self::stepped(self.a),
            r: self.gravity(self.r),
        }
    }

    /// Smooth (C¹) at 1: x² below, 2x − 1 above, times a gain chosen by a parameter: a branch
    /// on parameters and an early `return` on the state inside a helper.
    #[odyn::function]
    fn ramp(&self, x: f64) -> f64 {
        let k = if self.soft {
            self.k * self.scale
        } else {
            self.k
        };
        if x > 1.0 {
            return k * (2.0 * x - 1.0);
        }
        k * x * x
    }

    /// Not differentiable by odyn (`floor`), and called only on parameters: evaluated by the
    /// user's code, as any call on parameters.
    #[odyn::function]
    fn stepped(x: f64) -> f64 {
        x.floor()
    }

    #[odyn::function]
    fn polar(x: f64, y: f64) -> (f64, f64) {
        (x.hypot(y), y.atan2(x))
    }

    #[odyn::function]
    fn gravity(&self, r: Vector2<f64>) -> Vector2<f64> {
        -self.gm * r / r.norm().powi(3)
    }

    #[odyn::function]
    fn drive(&self, t: f64) -> f64 {
        self.a * (2.0 * t).sin()
    }
}

#[test]
fn helpers_with_branches_tuples_vectors_and_the_time_have_exact_derivatives() {
    let model = Helped {
        p: 0.0,
        q: 0.0,
        r: Vector2::zeros(),
        a: 1.7,
        gm: 2.0,
        scale: 0.5,
        k: 3.0,
        soft: true,
    };
    for t in [0.0, 0.4, 2.5] {
        check(&model, t, 100, |r| HelpedState {
            // p − q on both sides of the ramp's switch at 1.
            p: r.uniform(-2.0, 3.0),
            q: r.uniform(0.1, 1.0),
            r: Vector2::new(r.uniform(0.5, 2.0), r.uniform(-2.0, -0.5)),
        });
    }
    // ∂f/∂t flows through `drive` exactly: ∂ṗ/∂t = 2a·cos(2t)·cos(atan2(q, p)).
    const { assert!(<Helped as odyn::Jacobian>::TIME_DEPENDENT) };
    let y = HelpedState {
        p: 0.8,
        q: 0.3,
        r: Vector2::new(1.0, -1.0),
    };
    let t = 0.9;
    let mut dfdt = y;
    model.time_derivative(t, &y, &mut dfdt);
    let exact = 2.0 * 1.7 * (2.0 * t).cos() * 0.3f64.atan2(0.8).cos();
    assert!((dfdt.p - exact).abs() < 1e-14, "{} vs {exact}", dfdt.p);
    assert_eq!((dfdt.q, dfdt.r), (0.0, Vector2::zeros()));
    // The caller's `k` (2.2, floored to 2), not the helper's (1.5): at t = 0 the drive is 0, so
    // in the ramp's upper arm (p − q > 1) ∂ṗ/∂p = 2·1.5 − 2.
    let y = HelpedState {
        p: 2.5,
        q: 0.5,
        r: Vector2::new(1.0, -1.0),
    };
    let mut j = model.jacobian_matrix(&y);
    model.jacobian(0.0, &y, &mut j);
    assert_eq!(j[(0, 0)], 1.0);
    // The other arm of the helper's branch on `soft`: gain k = 3, so 2·3 − 2; and ∂q̇/∂q =
    // −floor(a).
    let hard = Helped {
        soft: false,
        ..model
    };
    hard.jacobian(0.0, &y, &mut j);
    assert_eq!(j[(0, 0)], 4.0);
    let radius = 0.5f64.hypot(2.5);
    let exact = radius.cos() * 0.5 / radius - 1.0;
    assert!(
        (j[(1, 1)] - exact).abs() < 1e-15,
        "{} vs {exact}",
        j[(1, 1)]
    );
    check(&hard, 0.3, 100, |r| HelpedState {
        p: r.uniform(-2.0, 3.0),
        q: r.uniform(0.1, 1.0),
        r: Vector2::new(r.uniform(0.5, 2.0), r.uniform(-2.0, -0.5)),
    });
}

/// Cables that pull only when stretched (as `particles::Cables`), the tension a helper of the
/// pair kernel given the link's parameters and the state.
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
        Self::tension(xb - xa, s.stiffness, s.rest)
    }

    #[odyn::function]
    fn tension(d: Vector3<f64>, k: f64, rest: f64) -> Vector3<f64> {
        let length = d.norm();
        if length > rest {
            d * (k * (length - rest) / length)
        } else {
            Vector3::zeros()
        }
    }
}

/// [`Cables`] inlined by hand.
#[system]
struct CablesInline {
    #[position]
    x: Vec<Vector3<f64>>,
    #[velocity]
    v: Vec<Vector3<f64>>,
    #[mass]
    mass: Vec<f64>,
    links: Vec<Spring>,
}

#[system]
impl CablesInline {
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
fn a_particle_kernel_calling_a_helper_has_the_hand_inlined_jacobian() {
    // The hand-inlined kernel's blocks are checked against central differences in
    // `particles::a_kernel_branching_on_the_state_matches_central_differences`; the helper's
    // are the same numbers, bit for bit (the same graph).
    let x: Vec<Vector3<f64>> = (0..6)
        .map(|i| {
            let i = f64::from(i);
            Vector3::new(i.cos(), (1.7 * i).sin(), 0.3 * i)
        })
        .collect();
    let links: Vec<Spring> = (0..6)
        .flat_map(|a| [(a, (a + 1) % 6), (a, (a + 3) % 6)])
        .map(|(a, b)| {
            let distance: f64 = (x[b] - x[a]).norm();
            Spring {
                a,
                b,
                // Taut and slack links, none near the switch.
                rest: distance * if a % 2 == 0 { 0.8 } else { 1.2 },
                stiffness: 40.0,
                damping: 0.0,
            }
        })
        .collect();
    let helped = Cables {
        v: vec![Vector3::zeros(); 6],
        mass: vec![1.0; 6],
        links: links.clone(),
        x: x.clone(),
    };
    let inline = CablesInline {
        v: vec![Vector3::zeros(); 6],
        mass: vec![1.0; 6],
        links,
        x,
    };
    let (state, other) = (helped.state(), inline.state());
    assert_eq!(state.as_slice(), other.as_slice());
    let (mut j, mut k) = (
        helped.jacobian_matrix(&state),
        inline.jacobian_matrix(&other),
    );
    helped.jacobian(0.0, &state, &mut j);
    inline.jacobian(0.0, &other, &mut k);
    let ((jx, jv), (kx, kv)) = (j.force_jacobians(), k.force_jacobians());
    assert!(jx.norm_max() > 1.0);
    assert_eq!((jx, jv), (kx, kv));
}

/// A grid cell whose reaction is a helper with an `if` on the cell's value (as
/// `grid::Threshold`'s).
#[system]
struct Reacting {
    #[field]
    u: Grid,
    d: f64,
}

#[system]
impl Reacting {
    #[cell]
    fn rate(&self, u: Stencil) -> f64 {
        Self::reaction(u.c) + self.d * u.laplacian()
    }

    #[odyn::function]
    fn reaction(c: f64) -> f64 {
        if c > 0.5 { c * (1.0 - c) } else { -c * c }
    }
}

/// [`Reacting`] inlined by hand.
#[system]
struct ReactingInline {
    #[field]
    u: Grid,
    d: f64,
}

#[system]
impl ReactingInline {
    #[cell]
    fn rate(&self, u: Stencil) -> f64 {
        (if u.c > 0.5 {
            u.c * (1.0 - u.c)
        } else {
            -u.c * u.c
        }) + self.d * u.laplacian()
    }
}

#[test]
fn a_grid_cell_calling_a_helper_has_the_hand_inlined_jacobian() {
    let value = |i: usize, j: usize| 0.05 + 0.9 * (((7 * i + 3 * j) % 11) as f64 / 10.0);
    let u = Grid::from_fn(6, 5, Boundary::Periodic, value).unwrap();
    let helped = Reacting {
        u: u.clone(),
        d: 0.7,
    };
    let inline = ReactingInline { u, d: 0.7 };
    let state = helped.state();
    let (mut j, mut k) = (
        helped.jacobian_matrix(&state),
        inline.jacobian_matrix(&state),
    );
    helped.jacobian(0.0, &state, &mut j);
    inline.jacobian(0.0, &state, &mut k);
    let (j, k) = (j.to_dense(), k.to_dense());
    // Both arms taken: −2c below 0.5, 1 − 2c above, and −4d on the diagonal from the Laplacian.
    assert!(j.norm_max() > 0.0);
    assert_eq!(j, k);
    let (mut f, mut g) = (state.clone(), state.clone());
    helped.derivative(0.0, &state, &mut f);
    inline.derivative(0.0, &state, &mut g);
    assert_eq!(f.as_slice(), g.as_slice());
}

/// A helper called in an arm of an `if` on the state, given a parameter, changing a local of its
/// own that has the name of one of its caller's: the helper's code runs in a block of its own,
/// so it neither changes the caller's `g` nor counts as the arm changing it.
#[system]
#[derive(Clone, Copy, Debug)]
struct Armed {
    #[state]
    x: f64,
    k: f64,
}

#[system]
impl Armed {
    fn derivative(&self) -> ArmedState {
        let g = self.k + 1.0;
        let y = if self.x > 0.0 {
            self.scaled(self.x, self.k)
        } else {
            -self.x
        };
        ArmedState {
            x: y * g.floor() - self.x,
        }
    }

    #[odyn::function]
    fn scaled(&self, x: f64, k: f64) -> f64 {
        let mut g = k;
        g *= 2.0;
        g * x * x
    }
}

#[test]
fn a_helper_in_an_arm_on_the_state_keeps_its_locals_to_itself() {
    let model = Armed { x: 0.0, k: 1.25 };
    check(&model, 0.0, 100, |r| ArmedState {
        x: if r.uniform(0.0, 1.0) < 0.5 {
            r.uniform(-2.0, -0.01)
        } else {
            r.uniform(0.01, 2.0)
        },
    });
    // x > 0: ẋ = 2k·x²·floor(k + 1) − x, so ∂ẋ/∂x = 4k·x·2 − 1 with the caller's g = 2.25.
    let mut j = model.jacobian_matrix(&model.state());
    model.jacobian(0.0, &ArmedState { x: 0.5 }, &mut j);
    assert_eq!(j[(0, 0)], 4.0 * 1.25 * 0.5 * 2.0 - 1.0);
}

/// A force odyn cannot see inside: a crate-style free function (not `#[odyn::function]`), and a
/// measured force curve looked up in a table and interpolated. The macro evaluates both calls as
/// written and differentiates each by a central difference of the call
/// (`Jacobian::EXACT = false`); the chain rule around them stays exact.
fn stiffening(x: f64, k: f64) -> f64 {
    -k * x * (1.0 + x * x)
}

/// −x³ − x tabulated at 0.05 over [−3, 3] (121 points) and linearly interpolated: a lookup
/// table of the kind a measured spring curve comes in.
fn tabulated(x: f64) -> f64 {
    const STEP: f64 = 0.05;
    let s = ((x + 3.0) / STEP).clamp(0.0, 119.999_999);
    let i = s as usize;
    let f = s - i as f64;
    let at = |i: usize| {
        let x = -3.0 + i as f64 * STEP;
        -x * x * x - x
    };
    at(i) * (1.0 - f) + at(i + 1) * f
}

#[system(integrator = Rodas5P)]
#[derive(Clone, Copy, Debug)]
struct Opaque {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    k: f64,
    c: f64,
}

#[system]
impl Opaque {
    fn acceleration(&self) -> f64 {
        stiffening(self.x, self.k) + 0.5 * tabulated(self.x * self.v) - self.c * self.v
    }
}

#[test]
fn calls_odyn_cannot_see_inside_are_differentiated_by_differences_of_the_call() {
    use odyn::Jacobian;
    const { assert!(!<Opaque as Jacobian>::EXACT) };
    const { assert!(<Duffing as Jacobian>::EXACT) };
    let model = Opaque {
        x: 0.3,
        v: -0.2,
        k: 4.0,
        c: 50.0,
    };
    // Off the table's nodes, where a difference quotient straddles two segments (x·v within
    // 1e-3 of a multiple of 0.05), and inside it (|x·v| < 2.25).
    check(&model, 0.0, 50, |rng| {
        loop {
            let (x, v) = (rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5));
            let s = (x * v + 3.0) / 0.05;
            if (s - s.round()).abs() > 0.02 {
                break OpaqueState { x, v };
            }
        }
    });
}

/// Rodas5P on the model with opaque calls (c = 50: stiff against k = 4) against DOP853 on the
/// same model at rtol 1e-12 (an explicit method never uses the Jacobian): they agree to the
/// Rosenbrock run's tolerance, 1e-6, at t = 5.
#[test]
fn rodas5p_runs_on_a_model_with_opaque_calls() {
    let model = Opaque {
        x: 1.0,
        v: 0.0,
        k: 4.0,
        c: 50.0,
    };
    let run = |method: Method, rtol: f64| {
        model
            .simulate()
            .integrator(method)
            .tolerances(rtol, rtol * 1e-2)
            .duration(5.0)
            .run()
            .unwrap()
            .last()
            .state
    };
    let (rodas, reference) = (run(Method::Rodas5P, 1e-8), run(Method::Dop853, 1e-12));
    assert!(
        (rodas.x - reference.x).abs() < 1e-6 * reference.x.abs().max(1e-3),
        "{rodas:?} against {reference:?}"
    );
    assert!((rodas.v - reference.v).abs() < 1e-6 * reference.v.abs().max(1e-3));
}

/// A method of a number odyn does not differentiate itself (`to_radians`, `fract`) is called as
/// written and differentiated by a central difference of the call: 1 for `fract` away from the
/// integers, π/180 for `to_radians`.
#[system]
#[derive(Clone, Copy, Debug)]
struct Sawtooth {
    #[state]
    x: f64,
    #[state]
    y: f64,
}

#[system]
impl Sawtooth {
    fn derivative(&self) -> SawtoothState {
        SawtoothState {
            x: -self.x.fract() * self.y,
            y: self.x.to_radians().sin() + self.y.mul_add(2.0, 1.0),
        }
    }
}

#[test]
fn unknown_methods_of_numbers_are_differentiated_by_differences_of_the_call() {
    use odyn::Jacobian;
    const { assert!(!<Sawtooth as Jacobian>::EXACT) };
    // Off the integers, where `fract` jumps.
    check(&Sawtooth { x: 0.5, y: 1.0 }, 0.0, 50, |rng| {
        loop {
            let (x, y) = (rng.uniform(-3.0, 3.0), rng.uniform(-2.0, 2.0));
            if (x - x.round()).abs() > 0.01 {
                break SawtoothState { x, y };
            }
        }
    });
}
