//! The V-cycle: down the levels a forward block Gauss–Seidel sweep and the restricted residual,
//! the coarsest level solved exactly, then up the levels the prolonged correction and a backward
//! sweep.

use faer::dyn_stack::MemStack;
use faer::linalg::lu::partial_pivoting::solve;
use faer::perm::PermRef;
use faer::{Conj, MatMut, Par};

use super::Multigrid;
use super::blocks::subtract_product;
use super::level::Level;

impl Multigrid {
    /// Unknowns of level l (the coarsest at l = levels).
    fn unknowns(&self, l: usize) -> usize {
        self.levels
            .get(l)
            .map_or(self.coarsest.rows(), |level| level.a.rows())
            * self.b
    }

    /// The length of the work vectors of one V-cycle: one block's room, then x, f and t
    /// (iterate, right-hand side, residual) of each level, then the coarsest's right-hand side
    /// (solved in place).
    pub(super) fn work_len(&self) -> usize {
        self.b
            + (0..self.levels.len())
                .map(|l| 3 * self.unknowns(l))
                .sum::<usize>()
            + self.unknowns(self.levels.len())
    }

    /// out = V·r, one V-cycle from a zero guess.
    pub(super) fn apply(&self, out: &mut [f64], r: &[f64], stack: &mut MemStack) {
        // Constant block sizes unroll the block kernels.
        match self.b {
            1 => self.cycle(1, out, r, stack),
            2 => self.cycle(2, out, r, stack),
            3 => self.cycle(3, out, r, stack),
            b => self.cycle(b, out, r, stack),
        }
    }

    /// [`Multigrid::apply`] with the block size `b`.
    #[inline(always)]
    fn cycle(&self, b: usize, out: &mut [f64], r: &[f64], stack: &mut MemStack) {
        let depth = self.levels.len();
        let (mut buffer, stack) = stack.make_with(self.work_len(), |_| 0.0f64);
        let (block, vectors) = buffer.split_at_mut(b);
        // Level l's x, f, t from the front of `vectors`, and the rest.
        fn split(v: &mut [f64], n: usize) -> (&mut [f64], &mut [f64], &mut [f64], &mut [f64]) {
            let (x, v) = v.split_at_mut(n);
            let (f, v) = v.split_at_mut(n);
            let (t, v) = v.split_at_mut(n);
            (x, f, t, v)
        }
        // The right-hand side of the level at the front of `v` (`last` for the coarsest).
        fn rhs(v: &mut [f64], n: usize, last: bool) -> &mut [f64] {
            if last { &mut v[..n] } else { &mut v[n..2 * n] }
        }
        // Into group order.
        for (fi, &unknown) in rhs(vectors, self.unknowns(0), depth == 0)
            .iter_mut()
            .zip(&self.index)
        {
            *fi = r[unknown];
        }
        // Down: smooth from zero, restrict the residual.
        let mut rest: &mut [f64] = &mut *vectors;
        for (l, level) in self.levels.iter().enumerate() {
            let (x, f, t, tail) = split(rest, self.unknowns(l));
            level.smooth_from_zero(b, x, f, block);
            level.residual_after_sweep(b, x, t);
            level.restrict(b, t, rhs(tail, self.unknowns(l + 1), l + 1 == depth));
            rest = tail;
        }
        // The coarsest, exactly, in place.
        let n = self.unknowns(depth);
        solve::solve_in_place_with_conj(
            self.lu.as_ref(),
            self.lu.as_ref(),
            PermRef::new_checked(&self.forward, &self.inverse, n),
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut rest[..n], n, 1),
            Par::Seq,
            stack,
        );
        // Up: prolong the correction, smooth.
        for l in (0..depth).rev() {
            let start: usize = (0..l).map(|k| 3 * self.unknowns(k)).sum();
            let (x, f, _, tail) = split(&mut vectors[start..], self.unknowns(l));
            let coarse = &tail[..self.unknowns(l + 1)];
            let level = &self.levels[l];
            level.prolong(b, coarse, x);
            level.smooth_backward(b, x, f, block);
        }
        for (&xi, &unknown) in vectors[..self.unknowns(0)].iter().zip(&self.index) {
            out[unknown] = xi;
        }
    }
}

impl Level {
    /// One forward block Gauss–Seidel sweep on A·x = f from x = 0, x written: the blocks right
    /// of the diagonal meet only zeros, so they are not read (the same x as [`Level::smooth`]
    /// from zero, to the bit).
    #[inline(always)]
    fn smooth_from_zero(&self, b: usize, x: &mut [f64], f: &[f64], s: &mut [f64]) {
        let bb = b * b;
        for k in 0..self.a.rows() {
            s.copy_from_slice(&f[k * b..(k + 1) * b]);
            // Block columns ascend: those below k come first.
            for p in self.a.row(k) {
                let g = self.a.column[p];
                if g >= k {
                    break;
                }
                subtract_product(b, self.a.block(p, b), &x[g * b..(g + 1) * b], s);
            }
            let inverse = &self.inverse[k * bb..(k + 1) * bb];
            for r in 0..b {
                x[k * b + r] = inverse[r * b..(r + 1) * b]
                    .iter()
                    .zip(s.iter())
                    .map(|(m, v)| m * v)
                    .sum();
            }
        }
    }

    /// t = f − A·x right after [`Level::smooth_from_zero`], as −U·x with U the blocks right of
    /// the diagonal: the sweep left f_k − Σ_{g ≤ k} A_kg·x_g zero (to the rounding of D_k⁻¹),
    /// so the residual needs neither f nor the blocks left of and on the diagonal — 3 of 5 on a
    /// 5-point grid.
    #[inline(always)]
    fn residual_after_sweep(&self, b: usize, x: &[f64], t: &mut [f64]) {
        t.fill(0.0);
        for k in 0..self.a.rows() {
            let tk = &mut t[k * b..(k + 1) * b];
            for p in self.a.row(k).rev() {
                let g = self.a.column[p];
                if g <= k {
                    break;
                }
                subtract_product(b, self.a.block(p, b), &x[g * b..(g + 1) * b], tk);
            }
        }
    }

    /// One backward block Gauss–Seidel sweep on A·x = f.
    #[inline(always)]
    fn smooth_backward(&self, b: usize, x: &mut [f64], f: &[f64], s: &mut [f64]) {
        for k in (0..self.a.rows()).rev() {
            self.relax(b, k, x, f, s);
        }
    }

    /// x_k = D_k⁻¹·(f_k − Σ_{g ≠ k} A_kg·x_g).
    #[inline(always)]
    fn relax(&self, b: usize, k: usize, x: &mut [f64], f: &[f64], s: &mut [f64]) {
        let bb = b * b;
        s.copy_from_slice(&f[k * b..(k + 1) * b]);
        for p in self.a.row(k) {
            let g = self.a.column[p];
            if g != k {
                subtract_product(b, self.a.block(p, b), &x[g * b..(g + 1) * b], s);
            }
        }
        let inverse = &self.inverse[k * bb..(k + 1) * bb];
        for r in 0..b {
            x[k * b + r] = inverse[r * b..(r + 1) * b]
                .iter()
                .zip(s.iter())
                .map(|(m, v)| m * v)
                .sum();
        }
    }

    /// coarse = Pᵀ·t.
    #[inline(always)]
    fn restrict(&self, b: usize, t: &[f64], coarse: &mut [f64]) {
        coarse.fill(0.0);
        for k in 0..self.p.rows() {
            let tk = &t[k * b..(k + 1) * b];
            for q in self.p.row(k) {
                let c = self.p.column[q];
                let block = self.p.block(q, b);
                for col in 0..b {
                    coarse[c * b + col] += (0..b).map(|r| block[r * b + col] * tk[r]).sum::<f64>();
                }
            }
        }
    }

    /// x += P·coarse.
    #[inline(always)]
    fn prolong(&self, b: usize, coarse: &[f64], x: &mut [f64]) {
        for k in 0..self.p.rows() {
            for q in self.p.row(k) {
                let c = self.p.column[q];
                let block = self.p.block(q, b);
                for r in 0..b {
                    x[k * b + r] += block[r * b..(r + 1) * b]
                        .iter()
                        .zip(&coarse[c * b..(c + 1) * b])
                        .map(|(m, v)| m * v)
                        .sum::<f64>();
                }
            }
        }
    }
}
