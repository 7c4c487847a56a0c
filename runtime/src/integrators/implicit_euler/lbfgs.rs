//! The history of L-BFGS and its two-loop recursion (Nocedal & Wright, *Numerical
//! Optimization*, 2nd ed., Springer 2006, Algorithm 7.4).

/// The last `capacity` pairs (sᵢ, yᵢ) of updates and gradient changes, in a ring, allocated once.
pub(super) struct History {
    steps: Vec<Vec<f64>>,
    changes: Vec<Vec<f64>>,
    /// 1/(yᵢ·sᵢ).
    rho: Vec<f64>,
    /// The two-loop recursion's αᵢ.
    alpha: Vec<f64>,
    /// Pairs held.
    len: usize,
    /// Where the next pair goes.
    next: usize,
}

impl History {
    /// Room for `capacity` pairs of vectors of length `n`.
    pub(super) fn new(capacity: usize, n: usize) -> Self {
        History {
            steps: vec![vec![0.0; n]; capacity],
            changes: vec![vec![0.0; n]; capacity],
            rho: vec![0.0; capacity],
            alpha: vec![0.0; capacity],
            len: 0,
            next: 0,
        }
    }

    /// Forgets every pair.
    pub(super) fn clear(&mut self) {
        self.len = 0;
        self.next = 0;
    }

    /// Records the update `step` = α·p and the change of the gradient `new − old` it made, when
    /// their product is positive (the curvature condition that keeps the implied Hessian
    /// positive definite); otherwise the pair is skipped.
    pub(super) fn push(&mut self, alpha: f64, direction: &[f64], new: &[f64], old: &[f64]) {
        let capacity = self.steps.len();
        if capacity == 0 {
            return;
        }
        let (s, y) = (&mut self.steps[self.next], &mut self.changes[self.next]);
        let mut curvature = 0.0;
        for (((si, yi), p), (n, o)) in s
            .iter_mut()
            .zip(y.iter_mut())
            .zip(direction)
            .zip(new.iter().zip(old))
        {
            *si = alpha * p;
            *yi = n - o;
            curvature += *si * *yi;
        }
        if !(curvature > 0.0 && curvature.is_finite()) {
            return;
        }
        self.rho[self.next] = 1.0 / curvature;
        self.next = (self.next + 1) % capacity;
        self.len = (self.len + 1).min(capacity);
    }

    /// Overwrites `q` (a gradient) with H·q, H the L-BFGS inverse Hessian whose initial matrix
    /// is applied by `initial` (in place).
    pub(super) fn apply(&mut self, q: &mut [f64], initial: impl FnOnce(&mut [f64])) {
        let capacity = self.steps.len();
        let newest_first = (1..=self.len).map(|k| (self.next + capacity - k) % capacity);
        for i in newest_first {
            let a = self.rho[i] * dot(&self.steps[i], q);
            self.alpha[i] = a;
            for (qj, yj) in q.iter_mut().zip(&self.changes[i]) {
                *qj -= a * yj;
            }
        }
        initial(q);
        let oldest_first = (1..=self.len)
            .rev()
            .map(|k| (self.next + capacity - k) % capacity);
        for i in oldest_first {
            let b = self.rho[i] * dot(&self.changes[i], q);
            let a = self.alpha[i];
            for (qj, sj) in q.iter_mut().zip(&self.steps[i]) {
                *qj += (a - b) * sj;
            }
        }
    }
}

/// a·b.
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a quadratic ½xᵀAx with A = diag(1, 10, 100) and the initial matrix I, L-BFGS holding
    /// every pair is BFGS, which with exact line searches generates conjugate directions and so
    /// reaches the minimum in n = 3 steps (the quadratic termination of the Broyden class:
    /// Nocedal & Wright 2006, chapter 6).
    #[test]
    fn a_quadratic_is_minimised_in_n_steps() {
        let a = [1.0, 10.0, 100.0];
        let mut x = vec![1.0, 1.0, 1.0];
        let gradient = |x: &[f64]| -> Vec<f64> { x.iter().zip(&a).map(|(x, a)| a * x).collect() };
        let mut history = History::new(5, 3);
        let mut g = gradient(&x);
        for _ in 0..3 {
            let mut p = g.clone();
            history.apply(&mut p, |_| {});
            p.iter_mut().for_each(|v| *v = -*v);
            // Exact line search on the quadratic: α = −g·p / pᵀAp.
            let curvature: f64 = p.iter().zip(&a).map(|(p, a)| a * p * p).sum();
            let alpha = -dot(&g, &p) / curvature;
            x.iter_mut().zip(&p).for_each(|(x, p)| *x += alpha * p);
            let new = gradient(&x);
            history.push(alpha, &p, &new, &g);
            g = new;
        }
        assert!(g.iter().all(|g| g.abs() < 1e-10), "{g:?}");
    }
}
