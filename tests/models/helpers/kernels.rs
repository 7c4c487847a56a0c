//! Helpers called from a particle pair kernel and from a grid cell, against the same kernels
//! inlined by hand.

use odyn::nalgebra::Vector3;
use odyn::particles::Spring;
use odyn::prelude::*;

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
