//! Quadratic B-spline weights: the kernel of every particle–grid transfer, FLIP/APIC's and MPM's.
//!
//! N(r) = ¾ − r² for |r| < ½, ½(3/2 − |r|)² for ½ ≤ |r| < 3/2, 0 beyond (r in cells): C¹, and
//! three nodes a side per particle. Its partition of unity Σᵢ N = 1 and exact reproduction of
//! linear functions Σᵢ N·xᵢ = x make the transfers conserve mass and linear momentum; its inertia
//! tensor Σᵢ N·(xᵢ − x)(xᵢ − x)ᵀ = h²/4·I (the APIC paper's D, Jiang et al. 2015, §5.3) is the
//! same at every position, which is what lets APIC and MLS-MPM write D⁻¹ = 4/h² once.

/// The 3×3 grid nodes a particle touches and their weights along each axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Stencil {
    /// The lower-left node of the 3×3 block (column, row).
    pub base: [usize; 2],
    /// The particle's position in cells, relative to `base`: in [½, 3/2) on each axis.
    pub fx: [f64; 2],
    /// The weights of nodes base + 0, 1, 2 along x (`w[0]`) and y (`w[1]`).
    pub w: [[f64; 3]; 2],
}

impl Stencil {
    /// The stencil of a particle at `x` in cells (position over the cell size, minus the grid's
    /// offset), which the caller has checked is in [½, n − 3/2) on an axis of n nodes: `base`
    /// is then at most n − 3, and the truncating conversion is the floor.
    #[inline(always)]
    pub fn at(x: [f64; 2]) -> Stencil {
        let base = [(x[0] - 0.5) as usize, (x[1] - 0.5) as usize];
        let fx = [x[0] - base[0] as f64, x[1] - base[1] as f64];
        Stencil {
            base,
            fx,
            w: [weights(fx[0]), weights(fx[1])],
        }
    }
}

/// N at distances fx, fx − 1, fx − 2 from the three nodes (fx in [½, 3/2)).
#[inline(always)]
fn weights(fx: f64) -> [f64; 3] {
    let (a, b, c) = (1.5 - fx, fx - 1.0, fx - 0.5);
    [0.5 * a * a, 0.75 - b * b, 0.5 * c * c]
}

/// The first stencil row a particle at height `y` in cells writes, or None outside
/// [½, `rows` − 3/2) (NaN included): the key of its strip in the scatter (`strips.rs`).
#[inline(always)]
pub(crate) fn base_row(y: f64, rows: usize) -> Option<usize> {
    (y >= 0.5 && y < rows as f64 - 1.5).then_some((y - 0.5) as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Partition of unity, linear reproduction and the inertia h²/4 (in cells: ¼), at positions
    /// across a cell: the identities the transfers' conservation rests on.
    #[test]
    fn the_weights_reproduce_constants_and_lines_and_have_inertia_a_quarter() {
        for k in 0..=64 {
            let x = [3.5 + k as f64 / 64.0 * 0.999, 7.25];
            let s = Stencil::at(x);
            let (mut sum, mut first, mut second) = (0.0, [0.0; 2], [[0.0; 2]; 2]);
            for i in 0..3 {
                for j in 0..3 {
                    let w = s.w[0][i] * s.w[1][j];
                    let d = [(s.base[0] + i) as f64 - x[0], (s.base[1] + j) as f64 - x[1]];
                    sum += w;
                    for a in 0..2 {
                        first[a] += w * d[a];
                        for b in 0..2 {
                            second[a][b] += w * d[a] * d[b];
                        }
                    }
                }
            }
            assert!((sum - 1.0).abs() < 1e-15, "{sum}");
            assert!(first.iter().all(|f| f.abs() < 1e-15), "{first:?}");
            let quarter = [[0.25, 0.0], [0.0, 0.25]];
            for a in 0..2 {
                for b in 0..2 {
                    assert!((second[a][b] - quarter[a][b]).abs() < 1e-15, "{second:?}");
                }
            }
        }
    }

    #[test]
    fn rows_outside_the_grid_have_no_strip() {
        assert_eq!(base_row(0.5, 10), Some(0));
        assert_eq!(base_row(8.49, 10), Some(7));
        assert_eq!(base_row(8.5, 10), None);
        assert_eq!(base_row(0.49, 10), None);
        assert_eq!(base_row(f64::NAN, 10), None);
        assert_eq!(base_row(f64::INFINITY, 10), None);
    }
}
