//! The transistor amplifier of the Bari test set (`transamp.f` rev. 1.3; Hairer & Wanner,
//! *Solving ODEs II*, VI.1): eight node voltages, M·y′ = f(t, y) with a singular tridiagonal
//! M built from the capacitances C_k = k·10⁻⁶ F, driven by U_e(t) = 0.1·sin(200πt); and the
//! same DAE in semi-explicit form (`TRANSAMP_SE`), for solvers that find algebraic components
//! only as zero diagonal entries of M.

use super::problems::{Dae, column_major};

const UB: f64 = 6.0;
const UF: f64 = 0.026;
const ALPHA: f64 = 0.99;
const BETA: f64 = 1e-6;
const R0: f64 = 1000.0;
/// R₁ … R₉, all 9000 Ω; the start names R₁, R₂, R₅ and R₆ as the file does.
const RK: f64 = 9000.0;
const R1: f64 = RK;
const R2: f64 = RK;
const R5: f64 = RK;
const R6: f64 = RK;
/// The file's π, 3.1415926535897931086244, which is `std::f64::consts::PI`.
const PI: f64 = std::f64::consts::PI;
const C1: f64 = 1e-6;
const C2: f64 = 2e-6;
const C3: f64 = 3e-6;
const C4: f64 = 4e-6;
const C5: f64 = 5e-6;

fn f(t: f64, y: &[f64], f: &mut [f64]) {
    let uet = 0.1 * (200.0 * PI * t).sin();
    let fac1 = BETA * (((y[1] - y[2]) / UF).exp() - 1.0);
    let fac2 = BETA * (((y[4] - y[5]) / UF).exp() - 1.0);
    f[0] = (y[0] - uet) / R0;
    f[1] = y[1] / RK + (y[1] - UB) / RK + (1.0 - ALPHA) * fac1;
    f[2] = y[2] / RK - fac1;
    f[3] = (y[3] - UB) / RK + ALPHA * fac1;
    f[4] = y[4] / RK + (y[4] - UB) / RK + (1.0 - ALPHA) * fac2;
    f[5] = y[5] / RK - fac2;
    f[6] = (y[6] - UB) / RK + ALPHA * fac2;
    f[7] = y[7] / RK;
}

fn jacobian(_t: f64, y: &[f64], j: &mut [f64]) {
    let g1 = BETA * ((y[1] - y[2]) / UF).exp() / UF;
    let g2 = BETA * ((y[4] - y[5]) / UF).exp() / UF;
    let mut rows = [[0.0; 8]; 8];
    rows[0][0] = 1.0 / R0;
    rows[1][1] = 1.0 / RK + 1.0 / RK + (1.0 - ALPHA) * g1;
    rows[1][2] = -(1.0 - ALPHA) * g1;
    rows[2][1] = -g1;
    rows[2][2] = 1.0 / RK + g1;
    rows[3][1] = ALPHA * g1;
    rows[3][2] = -ALPHA * g1;
    rows[3][3] = 1.0 / RK;
    rows[4][4] = 1.0 / RK + 1.0 / RK + (1.0 - ALPHA) * g2;
    rows[4][5] = -(1.0 - ALPHA) * g2;
    rows[5][4] = -g2;
    rows[5][5] = 1.0 / RK + g2;
    rows[6][4] = ALPHA * g2;
    rows[6][5] = -ALPHA * g2;
    rows[6][6] = 1.0 / RK;
    rows[7][7] = 1.0 / RK;
    column_major(&rows, j);
}

/// The mass matrix (symmetric, so its column-major and row-major layouts agree).
#[rustfmt::skip]
const MASS: [f64; 64] = [
    -C1,  C1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
     C1, -C1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    0.0, 0.0, -C2, 0.0, 0.0, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0, -C3,  C3, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0,  C3, -C3, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0, 0.0, 0.0, -C4, 0.0, 0.0,
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -C5,  C5,
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0,  C5, -C5,
];

const Y0: [f64; 8] = [
    0.0,
    UB / (R2 / R1 + 1.0),
    UB / (R2 / R1 + 1.0),
    UB,
    UB / (R6 / R5 + 1.0),
    UB / (R6 / R5 + 1.0),
    UB,
    0.0,
];

/// y′(0): rows 1, 3, 4, 6, 7 of M·y′ = f, and the node equations (rows 1 + 2, 4 + 5, 7 + 8,
/// which span M's left null space) differentiated: (J₁ + J₂)·y′ + ∂(f₁ + f₂)/∂t = 0, … .
fn yp0() -> Vec<f64> {
    let mut fy = [0.0; 8];
    let mut j = [0.0; 64];
    f(0.0, &Y0, &mut fy);
    jacobian(0.0, &Y0, &mut j);
    let jac = |r: usize, c: usize| j[c * 8 + r];
    let mut a = [[0.0; 8]; 8];
    let mut b = fy;
    for r in 0..8 {
        a[r].copy_from_slice(&MASS[r * 8..r * 8 + 8]);
    }
    // ∂f₁/∂t at t = 0: −0.1·200π·cos(0)/R₀.
    let dfdt = [-0.1 * 200.0 * PI / R0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    for (first, second) in [(0, 1), (3, 4), (6, 7)] {
        for (c, entry) in a[second].iter_mut().enumerate() {
            *entry = jac(first, c) + jac(second, c);
        }
        b[second] = -(dfdt[first] + dfdt[second]);
    }
    solve(a, b).to_vec()
}

/// Gaussian elimination with partial pivoting.
fn solve(mut a: [[f64; 8]; 8], mut b: [f64; 8]) -> [f64; 8] {
    for c in 0..8 {
        let p = (c..8)
            .max_by(|&i, &k| a[i][c].abs().total_cmp(&a[k][c].abs()))
            .expect("a column below the diagonal");
        a.swap(c, p);
        b.swap(c, p);
        let (top, below) = a.split_at_mut(c + 1);
        let pivot = &top[c];
        for (r, row) in below.iter_mut().enumerate() {
            let m = row[c] / pivot[c];
            for (x, p) in row[c..].iter_mut().zip(&pivot[c..]) {
                *x -= m * p;
            }
            b[c + 1 + r] -= m * b[c];
        }
    }
    for r in (0..8).rev() {
        for k in r + 1..8 {
            b[r] -= a[r][k] * b[k];
        }
        b[r] /= a[r][r];
    }
    b
}

pub const TRANSAMP: Dae = Dae {
    name: "transamp",
    n: 8,
    t_end: 0.2,
    atol_scale: 1e-4,
    f,
    jacobian,
    mass: &MASS,
    y0: &Y0,
    yp0,
    published: <[f64]>::to_vec,
    reference: &REFERENCE,
};

/// y(0.2): transamp.f, solut (PSIDE on a Cray C90, rtol = atol = 1e-14).
const REFERENCE: [f64; 8] = [
    -0.5562145012262709e-002,
    0.3006522471903042e+001,
    0.2849958788608128e+001,
    0.2926422536206241e+001,
    0.2704617865010554e+001,
    0.2761837778393145e+001,
    0.4770927631616772e+001,
    0.1236995868091548e+001,
];

// ---------------------------------------------------------------------------------------------
// Semi-explicit form

/// The unknowns z = (y₁ − y₂, y₃, y₄ − y₅, y₆, y₇ − y₈, y₂, y₅, y₈) (five capacitor voltages,
/// then three node voltages) back to y.
fn node_voltages(z: &[f64]) -> [f64; 8] {
    [
        z[0] + z[5],
        z[5],
        z[1],
        z[2] + z[6],
        z[6],
        z[3],
        z[4] + z[7],
        z[7],
    ]
}

/// y to z (`node_voltages` inverted).
fn capacitor_voltages(y: &[f64]) -> Vec<f64> {
    vec![
        y[0] - y[1],
        y[2],
        y[3] - y[4],
        y[5],
        y[6] - y[7],
        y[1],
        y[4],
        y[7],
    ]
}

/// The rows of the semi-explicit form from those of M·y′ = f: rows 1, 3, 4, 6, 7 (each the
/// current through one capacitor), then the node equations 1 + 2, 4 + 5, 7 + 8.
fn semi_explicit_rows(v: &[f64; 8]) -> [f64; 8] {
    [
        v[0],
        v[2],
        v[3],
        v[5],
        v[6],
        v[0] + v[1],
        v[3] + v[4],
        v[6] + v[7],
    ]
}

fn se_f(t: f64, z: &[f64], out: &mut [f64]) {
    let mut fy = [0.0; 8];
    f(t, &node_voltages(z), &mut fy);
    out.copy_from_slice(&semi_explicit_rows(&fy));
}

/// R·J(y)·T with R the row combination and T = ∂y/∂z.
fn se_jacobian(t: f64, z: &[f64], out: &mut [f64]) {
    let mut j = [0.0; 64];
    jacobian(t, &node_voltages(z), &mut j);
    // Columns of J·T: ∂y/∂z_c is column c of T.
    let t_columns: [&[usize]; 8] = [&[0], &[2], &[3], &[5], &[6], &[0, 1], &[3, 4], &[6, 7]];
    for (c, ys) in t_columns.iter().enumerate() {
        let mut column = [0.0; 8];
        for &k in *ys {
            for (r, v) in column.iter_mut().enumerate() {
                *v += j[k * 8 + r];
            }
        }
        out[c * 8..c * 8 + 8].copy_from_slice(&semi_explicit_rows(&column));
    }
}

#[rustfmt::skip]
const SE_MASS: [f64; 64] = {
    let mut m = [0.0; 64];
    let c = [-C1, -C2, -C3, -C4, -C5];
    let mut k = 0;
    while k < 5 {
        m[k * 8 + k] = c[k];
        k += 1;
    }
    m
};

const SE_Y0: [f64; 8] = [
    Y0[0] - Y0[1],
    Y0[2],
    Y0[3] - Y0[4],
    Y0[5],
    Y0[6] - Y0[7],
    Y0[1],
    Y0[4],
    Y0[7],
];

/// The amplifier as the same DAE in semi-explicit form: unknowns z (`node_voltages`),
/// M = diag(−C₁, −C₂, −C₃, −C₄, −C₅, 0, 0, 0), the node equations as the three algebraic rows.
/// A row combination and a change of unknowns, both constant and invertible: the solution is
/// the published one, and errors are measured in y.
pub const TRANSAMP_SE: Dae = Dae {
    name: "transamp_se",
    n: 8,
    t_end: 0.2,
    atol_scale: 1e-4,
    f: se_f,
    jacobian: se_jacobian,
    mass: &SE_MASS,
    y0: &SE_Y0,
    yp0: || capacitor_voltages(&yp0()),
    reference: &REFERENCE,
    published: |z| node_voltages(z).to_vec(),
};
