//! The particle-to-grid scatter in parallel, with the same sums for any thread count.
//!
//! A particle whose stencil starts at row r writes rows r, r + 1, r + 2 (`bspline.rs`). The
//! grid's rows are cut into strips of at least [`MIN_ROWS`] rows, each holding about the same
//! number of particles (about 1/[`STRIPS`] of them, by a count of the particles per row), and
//! the particles are sorted by strip (a counting sort, stable: by index within a strip). Strip s,
//! rows [aₛ, aₛ₊₁), then writes rows [aₛ, aₛ₊₁ + 2) only, so strips of the same parity write
//! disjoint rows and run in parallel: first the even strips, then the odd ones, each strip's
//! particles in order. Every node's sum is then taken in one order — its even strip's
//! particles, then its odd strip's — fixed by the positions alone (the strips' edges are too),
//! never by how rayon shares the strips among threads. The disjoint rows are handed out as
//! `&mut` parts of the grid split at the strips' edges, so no lock, atomic or unsafe code is
//! needed.
//!
//! Strips of equal particle counts keep both threads busy to the end of each pass where
//! particles crowd into a few rows (a splash on the floor); the row band a strip touches stays
//! in cache while its particles scatter into it, where a serial scatter in particle order
//! writes all over the grid.

/// Strips the rows are cut into, about (fewer when the particles span fewer than
/// 2·`STRIPS` rows): 16 tasks a pass, enough to balance a few threads.
pub(crate) const STRIPS: usize = 32;

/// Rows of a strip at least: strip s writes 2 rows into strip s + 1, never into s + 2.
pub(crate) const MIN_ROWS: usize = 2;

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
    /// Strip s is rows `edges[s]..edges[s + 1]`; the last edge is the grid's row count.
    edges: Vec<usize>,
    /// Particles of strip s: `order[start[s]..start[s + 1]]`.
    start: Vec<usize>,
    /// Particle indices, strip by strip, ascending within a strip.
    order: Vec<u32>,
    /// Per row: its particles while sorting, then its strip.
    row: Vec<usize>,
    /// Per strip, while sorting: where its next particle goes in `order`.
    cursor: Vec<usize>,
    /// The lowest and highest stencil rows of any particle (an empty range when there are no
    /// particles): the grid outside rows [low, high + 3) is untouched.
    rows: (usize, usize),
}

impl Strips {
    /// Sorts particles whose stencils start at the rows `base` (every row below `grid_rows` −
    /// 2) into strips.
    pub(crate) fn sort(&mut self, base: &[u32], grid_rows: usize) {
        self.row.clear();
        self.row.resize(grid_rows, 0);
        let (mut low, mut high) = (usize::MAX, 0);
        for &r in base {
            let r = r as usize;
            low = low.min(r);
            high = high.max(r);
            self.row[r] += 1;
        }
        self.rows = (low, high);
        // A strip closes once it holds its share and spans MIN_ROWS rows, leaving the last
        // strip MIN_ROWS rows at least.
        let share = base.len().div_ceil(STRIPS).max(1);
        self.edges.clear();
        self.edges.push(0);
        self.start.clear();
        self.start.push(0);
        let (mut held, mut before) = (0, 0);
        for r in 0..grid_rows {
            held += self.row[r];
            let edge = self.edges[self.edges.len() - 1];
            self.row[r] = self.edges.len() - 1;
            if held >= share && r + 1 - edge >= MIN_ROWS && r + 1 + MIN_ROWS <= grid_rows {
                self.edges.push(r + 1);
                before += held;
                self.start.push(before);
                held = 0;
            }
        }
        self.edges.push(grid_rows.max(1));
        self.start.push(base.len());
        // Each strip's next free slot in `order`, from where the strip begins.
        self.cursor.clear();
        self.cursor
            .extend_from_slice(&self.start[..self.start.len() - 1]);
        self.order.resize(base.len(), 0);
        for (p, &r) in base.iter().enumerate() {
            let slot = &mut self.cursor[self.row[r as usize]];
            self.order[*slot] = p as u32;
            *slot += 1;
        }
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
    /// once to `finish(rows, first_row)` after every particle has: the even pass's bands,
    /// strips 2k and 2k + 1, tile the grid, so each prepares its band and then scatters strip 2k;
    /// the odd pass's bands, strips 2k + 1 and 2k + 2, scatter strip 2k + 1 and then finish their
    /// band, which no later strip reaches (strip s writes 2 rows past its end, inside strip
    /// s + 1); strip 0's rows are finished between the passes. Zeroing the grid and updating
    /// its nodes ride in the scatter's two passes instead of passes of their own.
    pub(crate) fn scatter<T: Send>(
        &self,
        grid: &mut [T],
        row_len: usize,
        prepare: impl Fn(&mut [T], usize) + Sync,
        scatter: impl Fn(&mut [T], usize, &[u32]) + Sync,
        finish: impl Fn(&mut [T], usize) + Sync,
    ) {
        let strips = self.edges.len().saturating_sub(1);
        if strips == 0 {
            return;
        }
        let parallel = parallel(self.order.len());
        let strip = |s: usize, rows: &mut [T], first: usize| {
            if s < strips {
                let particles = &self.order[self.start[s]..self.start[s + 1]];
                if !particles.is_empty() {
                    scatter(rows, first, particles);
                }
            }
        };
        let bands = Bands {
            edges: &self.edges,
            row_len,
            parallel,
        };
        bands.run(grid, 0, 0, strips.div_ceil(2), &|k, rows, first| {
            prepare(rows, first);
            strip(2 * k, rows, first);
        });
        let head = self.edges[1];
        let (head_rows, rest) = grid.split_at_mut((head * row_len).min(grid.len()));
        finish(head_rows, 0);
        if strips > 1 {
            bands.run(rest, 1, 0, strips / 2, &|k, rows, first| {
                strip(2 * k + 1, rows, first);
                finish(rows, first);
            });
        }
    }
}

/// The grid cut at every other strip edge: band k of a pass that starts at strip `from` is
/// strips `from` + 2k and `from` + 2k + 1.
struct Bands<'a> {
    edges: &'a [usize],
    row_len: usize,
    parallel: bool,
}

impl Bands<'_> {
    /// The first row of band k of the pass from strip `from` (the grid's end past the last).
    fn edge(&self, from: usize, k: usize) -> usize {
        self.edges[(from + 2 * k).min(self.edges.len() - 1)]
    }

    /// Runs `task(k, rows, first_row)` for bands `low..high` of the pass from strip `from`,
    /// `rows` starting at band `low`'s first row: halves of the bands on two of rayon's threads,
    /// recursively, when the pass is parallel.
    fn run<T: Send>(
        &self,
        rows: &mut [T],
        from: usize,
        low: usize,
        high: usize,
        task: &(impl Fn(usize, &mut [T], usize) + Sync),
    ) {
        let first = self.edge(from, low);
        if high - low == 1 {
            task(low, rows, first);
            return;
        }
        let middle = (low + high) / 2;
        let split = ((self.edge(from, middle) - first) * self.row_len).min(rows.len());
        let (left, right) = rows.split_at_mut(split);
        if self.parallel {
            rayon::join(
                || self.run(left, from, low, middle, task),
                || self.run(right, from, middle, high, task),
            );
        } else {
            self.run(left, from, low, middle, task);
            self.run(right, from, middle, high, task);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `f` run in a pool of its own with `threads` threads.
    fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(f)
    }

    /// Every particle lands in its strip, in index order; strips span MIN_ROWS rows at least
    /// and hold about a STRIPS-th of the particles each; and a scatter of each particle's index
    /// onto its rows sums the same whatever the thread count.
    #[test]
    fn strips_hold_their_particles_in_order_and_scatter_the_same_on_any_pool() {
        let rows = 23;
        let mut draw = crate::linalg::generator(7);
        // Crowded into rows 12–15, with a few particles elsewhere (a splash on the floor).
        let base: Vec<u32> = (0..5000)
            .map(|p| {
                let r = draw() % (rows - 2);
                (if p % 10 == 0 { r } else { 12 + r % 4 }) as u32
            })
            .collect();
        let mut strips = Strips::default();
        strips.sort(&base, rows);
        assert_eq!(strips.order.len(), base.len());
        assert_eq!(strips.edges.first(), Some(&0));
        assert_eq!(strips.edges.last(), Some(&rows));
        for s in 0..strips.edges.len() - 1 {
            let (low, high) = (strips.edges[s], strips.edges[s + 1]);
            assert!(high - low >= MIN_ROWS, "strip {s}: rows {low}..{high}");
            let members = &strips.order[strips.start[s]..strips.start[s + 1]];
            assert!(members.windows(2).all(|w| w[0] < w[1]));
            assert!(
                members
                    .iter()
                    .all(|&p| (low..high).contains(&(base[p as usize] as usize)))
            );
        }
        // Four crowded rows of 4 500 particles in strips of 2 rows: no strip holds more
        // than two of them (2 250), against 4 500 in the crowded strip of a fixed 4-row cut.
        assert!(strips.start.windows(2).all(|w| w[1] - w[0] <= 2 * 1200));
        let run = |threads| {
            in_pool(threads, || {
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

    /// Hostile layouts: no particles, one, all in one row, every row, grids of 3 to 9 rows and
    /// more particles than a strip's share in every row. Each row is prepared once before any
    /// particle adds to it and finished once after, every particle adds once, and 1 and 3
    /// threads give the same grid.
    #[test]
    fn every_row_is_prepared_and_finished_once_in_any_layout() {
        let layouts: Vec<(usize, Vec<u32>)> = vec![
            (3, vec![]),
            (3, vec![0]),
            (4, vec![1, 1, 1]),
            (5, vec![2; 100]),
            (9, (0..7).collect()),
            (9, (0..7000).map(|p| (p % 7) as u32).collect()),
            (40, vec![37; 10]),
            (40, (0..38).rev().collect()),
        ];
        for (rows, base) in layouts {
            let mut strips = Strips::default();
            strips.sort(&base, rows);
            let run = |threads| {
                // Per row: [prepared, particles added, finished], with NaN until prepared.
                in_pool(threads, || {
                    let mut grid = vec![[f64::NAN, f64::NAN, 0.0]; rows];
                    strips.scatter(
                        &mut grid,
                        1,
                        |band, _| band.iter_mut().for_each(|row| *row = [1.0, 0.0, 0.0]),
                        |band, first, particles| {
                            for &p in particles {
                                for k in 0..3 {
                                    let row = &mut band[base[p as usize] as usize + k - first];
                                    assert_eq!(row[2], 0.0, "added to after its finish");
                                    row[1] += 1.0;
                                }
                            }
                        },
                        |band, _| band.iter_mut().for_each(|row| row[2] += 1.0),
                    );
                    grid
                })
            };
            let one = run(1);
            assert_eq!(one, run(3), "{rows} rows, {} particles", base.len());
            assert!(one.iter().all(|row| row[0] == 1.0 && row[2] == 1.0));
            let added: f64 = one.iter().map(|row| row[1]).sum();
            assert_eq!(added, 3.0 * base.len() as f64);
        }
    }
}
