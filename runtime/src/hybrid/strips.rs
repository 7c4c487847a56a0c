//! The particle-to-grid scatter in parallel, with the same sums for any thread count.
//!
//! A particle whose stencil starts at row r writes rows r, r + 1, r + 2 (`bspline.rs`). The
//! particles are sorted by r into strips of [`ROWS`] rows (a counting sort, stable: by index
//! within a strip), so strip s writes rows [s·ROWS, s·ROWS + ROWS + 2) only. Strips of the same
//! parity then write disjoint rows (ROWS ≥ 2), and run in parallel: first the even strips, then
//! the odd ones, each strip's particles in order. Every node's sum is then taken in one order —
//! its even strip's particles, then its odd strip's — fixed by the positions alone, never by how
//! rayon shares the strips among threads. The disjoint rows are handed out as `&mut` chunks of
//! the grid (`par_chunks_mut`), so no lock, atomic or unsafe code is needed.
//!
//! The row band a strip touches (ROWS + 2 rows of the grid) stays in the first-level cache while
//! its particles scatter into it; a serial scatter in particle order writes all over the grid.

use rayon::prelude::*;

/// Rows of a strip: each parallel task scatters the particles of 4 stencil rows, writing 6.
pub(crate) const ROWS: usize = 4;

/// Particles from which the passes of a step run on rayon's threads.
pub(crate) const PARALLEL_FROM: usize = 4096;

/// Whether a pass over `particles` particles runs on rayon's threads: from [`PARALLEL_FROM`]
/// particles, in a pool of more than one thread. Otherwise the calling thread does the same
/// work in the same order (so the same bits) without handing the pass to the pool, which costs
/// microseconds a pass (a wake-up and a wait) from a thread outside it.
pub(crate) fn parallel(particles: usize) -> bool {
    particles >= PARALLEL_FROM && rayon::current_num_threads() > 1
}

/// The particles sorted by strip.
#[derive(Clone, Debug, Default)]
pub(crate) struct Strips {
    /// Particles of strip s: `order[start[s]..start[s + 1]]`.
    start: Vec<usize>,
    /// Particle indices, strip by strip, ascending within a strip.
    order: Vec<u32>,
    /// The lowest and highest stencil rows of any particle (an empty range when there are no
    /// particles): the grid outside rows [low, high + 3) is untouched.
    rows: (usize, usize),
}

impl Strips {
    /// Sorts particles whose stencils start at the rows `base` (every row below `grid_rows` −
    /// 2) into strips.
    pub(crate) fn sort(&mut self, base: &[u32], grid_rows: usize) {
        let strips = grid_rows.div_ceil(ROWS);
        self.start.clear();
        self.start.resize(strips + 2, 0);
        let (mut low, mut high) = (usize::MAX, 0);
        for &r in base {
            let r = r as usize;
            low = low.min(r);
            high = high.max(r);
            self.start[r / ROWS + 2] += 1;
        }
        self.rows = (low, high);
        for s in 2..self.start.len() {
            self.start[s] += self.start[s - 1];
        }
        // start[s + 1] now counts the particles of strips below s: where strip s begins.
        self.order.resize(base.len(), 0);
        for (p, &r) in base.iter().enumerate() {
            let slot = &mut self.start[r as usize / ROWS + 1];
            self.order[*slot] = p as u32;
            *slot += 1;
        }
        self.start.pop();
    }

    /// The rows a scatter writes, [low, high): empty with no particles.
    pub(crate) fn touched_rows(&self) -> std::ops::Range<usize> {
        if self.order.is_empty() {
            0..0
        } else {
            self.rows.0..self.rows.1 + 3
        }
    }

    /// Runs `scatter(rows, first_row, particles)` for every strip, even strips in parallel and
    /// then odd ones, `rows` the grid's rows from `first_row` on (`row_len` nodes each) that the
    /// strip may write, `particles` its particles in order.
    ///
    /// Each row is handed once to `prepare(rows, first_row)` before any particle adds to it, and
    /// once to `finish(rows, first_row)` after every particle has: the even pass's bands of
    /// 2·[`ROWS`] rows tile the grid, so each prepares its band and then scatters its strip;
    /// the odd pass's bands, [`ROWS`] rows up, scatter their strip and then finish their band,
    /// which no later strip reaches (strip s writes rows below (s + 1)·ROWS + 2 ≤ (s + 2)·ROWS);
    /// the first [`ROWS`] rows are finished between the passes. Zeroing the grid and updating
    /// its nodes ride in the scatter's two passes instead of passes of their own.
    pub(crate) fn scatter<T: Send>(
        &self,
        grid: &mut [T],
        row_len: usize,
        prepare: impl Fn(&mut [T], usize) + Sync,
        scatter: impl Fn(&mut [T], usize, &[u32]) + Sync,
        finish: impl Fn(&mut [T], usize) + Sync,
    ) {
        let band = 2 * ROWS * row_len;
        let strip = |s: usize, rows: &mut [T]| {
            if s + 1 < self.start.len() {
                let particles = &self.order[self.start[s]..self.start[s + 1]];
                if !particles.is_empty() {
                    scatter(rows, s * ROWS, particles);
                }
            }
        };
        let even = |(k, rows): (usize, &mut [T])| {
            prepare(rows, 2 * k * ROWS);
            strip(2 * k, rows);
        };
        let odd = |(k, rows): (usize, &mut [T])| {
            strip(2 * k + 1, rows);
            finish(rows, (2 * k + 1) * ROWS);
        };
        if !parallel(self.order.len()) {
            grid.chunks_mut(band).enumerate().for_each(even);
        } else {
            grid.par_chunks_mut(band).enumerate().for_each(even);
        }
        let (head, rest) = grid.split_at_mut((ROWS * row_len).min(grid.len()));
        finish(head, 0);
        if !parallel(self.order.len()) {
            rest.chunks_mut(band).enumerate().for_each(odd);
        } else {
            rest.par_chunks_mut(band).enumerate().for_each(odd);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every particle lands in its strip, in index order, and a scatter of each particle's
    /// index onto its rows sums the same whatever the thread count.
    #[test]
    fn strips_hold_their_particles_in_order_and_scatter_the_same_on_any_pool() {
        let rows = 23;
        let mut draw = crate::linalg::generator(7);
        let base: Vec<u32> = (0..5000).map(|_| (draw() % (rows - 2)) as u32).collect();
        let mut strips = Strips::default();
        strips.sort(&base, rows);
        assert_eq!(strips.order.len(), base.len());
        for s in 0..strips.start.len() - 1 {
            let members = &strips.order[strips.start[s]..strips.start[s + 1]];
            assert!(members.windows(2).all(|w| w[0] < w[1]));
            assert!(
                members
                    .iter()
                    .all(|&p| base[p as usize] as usize / ROWS == s)
            );
        }
        let run = |threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                // Each row is prepared (set to 0 from NaN) before any particle adds to it, and
                // finished (its first node counts the finishes) after all have.
                let mut grid = vec![f64::NAN; rows * 3];
                strips.scatter(
                    &mut grid,
                    3,
                    |band, _| band.fill(0.0),
                    |band, first, particles| {
                        for &p in particles {
                            let r = base[p as usize] as usize - first;
                            for k in 0..3 {
                                band[(r + k) * 3 + 1] += 1.0 / (1.0 + p as f64);
                            }
                        }
                    },
                    |band, _| {
                        for row in band.chunks_mut(3) {
                            row[0] += 1.0;
                        }
                    },
                );
                grid
            })
        };
        let one = run(1);
        assert_eq!(one, run(4));
        assert!(one.chunks(3).all(|row| row[0] == 1.0 && row[2] == 0.0));
        let total: f64 = one.chunks(3).map(|row| row[1]).sum();
        let expected: f64 = (0..5000).map(|p| 3.0 / (1.0 + p as f64)).sum();
        assert!((total - expected).abs() < 1e-12);
        assert_eq!(strips.touched_rows().end, rows);
    }
}
