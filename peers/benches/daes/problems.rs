//! Three index-1 DAEs in mass-matrix form M·y′ = f(t, y), transcribed with the constants and
//! the order of operations of their sources (the same as `peers/ida/problems.c` and
//! `scripts/reference_dae.py`; notes in `notes/dae-problems.md`):
//!
//! - `chemakzo`: Chemical Akzo Nobel, Bari test set (Mazzia & Magherini, *Test Set for IVP
//!   Solvers*, release 2.4, 2008) file `chemakzo.f` rev. 1.2, as vendored in MESAHub/mesa
//!   `num/test/src/bari_chemakzo.f` (commit 13fe30d5); M = diag(1, 1, 1, 1, 1, 0);
//! - `transamp`: Transistor amplifier, the test set's `transamp.f` rev. 1.3, as vendored in
//!   rforge/bvpsolve `pkg/deTestSet/src/Ex_transistor.f` (commit 14b319e0); M tridiagonal,
//!   singular (rank 5);
//! - `roberdae`: Robertson's kinetics with y₁ + y₂ + y₃ = 1 as the third row, M = diag(1, 1, 0);
//!   the reference is the 36-digit Radau IIA run of `scripts/reference_dae.py` (ODE form).
//!
//! Matrices are n × n, column-major (entry (r, c) at `c * n + r`), as nalgebra and SUNDIALS
//! store them.

#![allow(
    clippy::excessive_precision,
    reason = "reference values are quoted with every digit their sources print"
)]

/// A DAE M·y′ = f(t, y) on t ∈ [0, `t_end`] with a constant mass matrix.
pub struct Dae {
    /// The group name prefix of the bench.
    pub name: &'static str,
    pub n: usize,
    pub t_end: f64,
    /// atol = rtol · `atol_scale` in the calibration sweeps.
    pub atol_scale: f64,
    pub f: fn(f64, &[f64], &mut [f64]),
    /// J = ∂f/∂y, column-major.
    pub jacobian: fn(f64, &[f64], &mut [f64]),
    /// M, column-major.
    pub mass: &'static [f64],
    pub y0: &'static [f64],
    /// A y′(0) consistent with `y0` (exact: the algebraic rows differentiated once; see
    /// `peers/ida/problems.c`, `consistent_yp0`).
    pub yp0: fn() -> Vec<f64>,
    /// y(`t_end`) in the published problem's unknowns.
    pub reference: &'static [f64],
    /// A state in the published problem's unknowns, where errors are measured (the identity but
    /// for a reformulation).
    pub published: fn(&[f64]) -> Vec<f64>,
}

// ---------------------------------------------------------------------------------------------
// chemakzo

const K1: f64 = 18.7;
const K2: f64 = 0.58;
const K3: f64 = 0.09;
const K4: f64 = 0.42;
const KBIG: f64 = 34.4;
const KLA: f64 = 3.3;
const KS: f64 = 115.83;
const PO2: f64 = 0.9;
const HEN: f64 = 737.0;

fn akzo_f(_t: f64, y: &[f64], f: &mut [f64]) {
    let sqy2 = y[1].sqrt();
    let r1 = K1 * y[0] * y[0] * y[0] * y[0] * sqy2;
    let r2 = K2 * y[2] * y[3];
    let r3 = K2 / KBIG * y[0] * y[4];
    let r4 = K3 * y[0] * y[3] * y[3];
    let r5 = K4 * (y[5] * y[5]) * sqy2;
    let fin = KLA * (PO2 / HEN - y[1]);
    f[0] = ((-2.0 * r1 + r2) - r3) - r4;
    f[1] = ((-0.5 * r1 - r4) - 0.5 * r5) + fin;
    f[2] = (r1 - r2) + r3;
    f[3] = (-r2 + r3) - 2.0 * r4;
    f[4] = (r2 - r3) + r5;
    f[5] = KS * y[0] * y[3] - y[5];
}

fn akzo_jacobian(_t: f64, y: &[f64], j: &mut [f64]) {
    let y13 = y[0] * y[0] * y[0];
    let sq = y[1].sqrt();
    let (r11, r12) = (4.0 * K1 * y13 * sq, 0.5 * K1 * y[0] * y13 / sq);
    let (r23, r24) = (K2 * y[3], K2 * y[2]);
    let (r31, r35) = ((K2 / KBIG) * y[4], (K2 / KBIG) * y[0]);
    let (r41, r44) = (K3 * y[3] * y[3], 2.0 * K3 * y[0] * y[3]);
    let (r52, r56) = (0.5 * K4 * y[5] * y[5] / sq, 2.0 * K4 * y[5] * sq);
    let rows: [[f64; 6]; 6] = [
        [
            (-2.0 * r11 - r31) - r41,
            -2.0 * r12,
            r23,
            r24 - r44,
            -r35,
            0.0,
        ],
        [
            -0.5 * r11 - r41,
            -0.5 * r12 - 0.5 * r52 - KLA,
            0.0,
            -r44,
            0.0,
            -0.5 * r56,
        ],
        [r11 + r31, r12, -r23, -r24, r35, 0.0],
        [r31 - 2.0 * r41, 0.0, -r23, -r24 - 2.0 * r44, r35, 0.0],
        [-r31, r52, r23, r24, -r35, r56],
        [KS * y[3], 0.0, 0.0, KS * y[0], 0.0, -1.0],
    ];
    column_major(&rows, j);
}

fn akzo_yp0() -> Vec<f64> {
    let y = CHEMAKZO.y0;
    let mut f = [0.0; 6];
    akzo_f(0.0, y, &mut f);
    // y₆ = Ks·y₁·y₄ differentiated.
    f[5] = KS * (f[0] * y[3] + y[0] * f[3]);
    f.to_vec()
}

pub const CHEMAKZO: Dae = Dae {
    name: "chemakzo",
    n: 6,
    t_end: 180.0,
    atol_scale: 1e-4,
    f: akzo_f,
    jacobian: akzo_jacobian,
    mass: &[
        1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    ],
    y0: &[0.444, 0.00123, 0.0, 0.007, 0.0, KS * 0.444 * 0.007],
    yp0: akzo_yp0,
    published: <[f64]>::to_vec,
    // chemakzo.f, solut: PSIDE on a Cray C90, rtol = atol = 1e-19.
    reference: &[
        0.1150794920661702e0,
        0.1203831471567715e-2,
        0.1611562887407974e0,
        0.3656156421249283e-3,
        0.1708010885264404e-1,
        0.4873531310307455e-2,
    ],
};

// ---------------------------------------------------------------------------------------------
// roberdae

fn rober_f(_t: f64, y: &[f64], f: &mut [f64]) {
    f[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
    f[1] = 0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1];
    f[2] = y[0] + y[1] + y[2] - 1.0;
}

fn rober_jacobian(_t: f64, y: &[f64], j: &mut [f64]) {
    let rows = [
        [-0.04, 1e4 * y[2], 1e4 * y[1]],
        [0.04, -1e4 * y[2] - 6e7 * y[1], -1e4 * y[1]],
        [1.0, 1.0, 1.0],
    ];
    column_major(&rows, j);
}

pub const ROBERDAE: Dae = Dae {
    name: "roberdae",
    n: 3,
    t_end: 1e11,
    atol_scale: 1e-8,
    f: rober_f,
    jacobian: rober_jacobian,
    mass: &[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
    y0: &[1.0, 0.0, 0.0],
    yp0: || vec![-0.04, 0.04, 0.0],
    published: <[f64]>::to_vec,
    // scripts/reference_dae.py: Radau IIA, 7 stages, 36 digits, rtol 1e-24, on the ODE form
    // (y₁ + y₂ + y₃ = 1 is its invariant); the test set's rober.f value agrees to 1.9e-14.
    reference: &[
        2.083340149701294e-08,
        8.333360770334784e-14,
        0.9999999791665152,
    ],
};

/// Writes the row-major `rows` into the column-major `out`.
pub fn column_major<const N: usize>(rows: &[[f64; N]; N], out: &mut [f64]) {
    for (r, row) in rows.iter().enumerate() {
        for (c, v) in row.iter().enumerate() {
            out[c * N + r] = *v;
        }
    }
}
