//! BiCGSTAB with right preconditioning (van der Vorst, "Bi-CGSTAB: a fast and smoothly
//! converging variant of Bi-CG for the solution of nonsymmetric linear systems", SIAM J. Sci.
//! Stat. Comput. 13(2):631–644, 1992), its vector updates fused into three passes an iteration
//! and its dot products taken inside the products by rows.
//!
//! faer's `bicgstab` serves any number of right-hand sides: per iteration it copies vectors four
//! times for its identity left preconditioner, solves 1 × 1 systems by a pivoted LU, and makes a
//! pass per update and per dot product, on its sparse product by columns. Here an iteration is
//! two products by rows ([`RowMatrix`]) with the dot products taken in them, two preconditioner
//! applications, and three passes over the vectors.

use faer::dyn_stack::MemStack;

use crate::linalg::krylov::NoConvergence;
use crate::linalg::operator::Column;
use crate::linalg::operator::Products;

/// The vectors of one solve, kept between solves.
#[derive(Clone, Debug)]
pub(super) struct Vectors {
    /// The residual r, and s = r − α·v in its place (r is not needed once s is made).
    r: Vec<f64>,
    /// The shadow residual r̂₀.
    shadow: Vec<f64>,
    p: Vec<f64>,
    /// K⁻¹·p.
    p_hat: Vec<f64>,
    /// A·K⁻¹·p.
    v: Vec<f64>,
    /// K⁻¹·s.
    s_hat: Vec<f64>,
    /// A·K⁻¹·s.
    t: Vec<f64>,
}

impl Vectors {
    pub(super) fn new(n: usize) -> Self {
        let zero = vec![0.0; n];
        Vectors {
            r: zero.clone(),
            shadow: zero.clone(),
            p: zero.clone(),
            p_hat: zero.clone(),
            v: zero.clone(),
            s_hat: zero.clone(),
            t: zero,
        }
    }
}

/// Solves A·x = b from the start in `x` (`zero_start` when it is zero, saving a product) to
/// ‖b − A·x‖₂ < `rtol`·‖b‖₂, as measured by the recursively updated residual; returns the
/// iterations taken, each a half step counting as one when it ends the solve (as faer counts).
///
/// Errors: [`NoConvergence`] after `max_iterations` iterations, or on a breakdown (a zero or
/// non-finite ρ, r̂₀·v or ω).
#[allow(clippy::too_many_arguments)] // reason: the operator, its preconditioner, the system and the stopping rule, each needed
pub(super) fn bicgstab(
    a: Products<'_>,
    k: &impl Column,
    b: &[f64],
    x: &mut [f64],
    zero_start: bool,
    rtol: f64,
    max_iterations: usize,
    work: &mut Vectors,
    stack: &mut MemStack,
) -> Result<usize, NoConvergence> {
    let Vectors {
        r,
        shadow,
        p,
        p_hat,
        v,
        s_hat,
        t,
    } = work;
    let b_norm = dot(b, b).sqrt();
    if b_norm == 0.0 {
        x.fill(0.0);
        return Ok(0);
    }
    let threshold = rtol * b_norm;
    let mut rr = if zero_start {
        r.copy_from_slice(b);
        b_norm * b_norm
    } else {
        a.product(x, r, b);
        let mut rr = 0.0;
        for (ri, bi) in r.iter_mut().zip(b) {
            *ri = bi - *ri;
            rr += *ri * *ri;
        }
        rr
    };
    if rr.sqrt() < threshold {
        return Ok(0);
    }
    shadow.copy_from_slice(r);
    p.copy_from_slice(r);
    let mut rho = rr;
    for iter in 1..=max_iterations {
        k.apply_column(p_hat, p, stack);
        let (shadow_v, _) = a.product(p_hat, v, shadow);
        let alpha = rho / shadow_v;
        if !(alpha.is_finite() && alpha != 0.0) {
            return Err(NoConvergence);
        }
        // s = r − α·v, in r's place.
        let s = &mut *r;
        let mut ss = 0.0;
        for (si, vi) in s.iter_mut().zip(v.iter()) {
            *si -= alpha * vi;
            ss += *si * *si;
        }
        if ss.sqrt() < threshold {
            for (xi, pi) in x.iter_mut().zip(p_hat.iter()) {
                *xi += alpha * pi;
            }
            return Ok(iter);
        }
        k.apply_column(s_hat, s, stack);
        let (ts, tt) = a.product(s_hat, t, s);
        let omega = ts / tt;
        if !(omega.is_finite() && omega != 0.0) {
            return Err(NoConvergence);
        }
        let mut rho_next = 0.0;
        rr = 0.0;
        // r = s − ω·t, in s's place.
        for ((((xi, ri), pi), s_hat_i), (ti, shadow_i)) in x
            .iter_mut()
            .zip(s.iter_mut())
            .zip(p_hat.iter())
            .zip(s_hat.iter())
            .zip(t.iter().zip(shadow.iter()))
        {
            *xi += alpha * pi + omega * s_hat_i;
            *ri -= omega * ti;
            rr += *ri * *ri;
            rho_next += shadow_i * *ri;
        }
        if rr.sqrt() < threshold {
            return Ok(iter);
        }
        let beta = (rho_next / rho) * (alpha / omega);
        if !(beta.is_finite() && rho_next != 0.0) {
            return Err(NoConvergence);
        }
        rho = rho_next;
        for ((pi, ri), vi) in p.iter_mut().zip(r.iter()).zip(v.iter()) {
            *pi = ri + beta * (*pi - omega * vi);
        }
    }
    Err(NoConvergence)
}

/// u·v, summed in order.
fn dot(u: &[f64], v: &[f64]) -> f64 {
    u.iter().zip(v).map(|(a, b)| a * b).sum()
}
