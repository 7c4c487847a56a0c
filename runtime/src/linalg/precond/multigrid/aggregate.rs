//! Aggregation: which groups of one level make each group of the next.

use super::blocks::Blocks;

/// Groups coupled to no other (a particle without links, a pinned one) are lumped into
/// aggregates of this many: they coarsen too, and the smoother solves them exactly anyway.
const LUMP: usize = 8;

/// Groups into aggregates (Vaněk, Mandel & Brezina 1996, §4): (0) groups coupled to no other
/// are lumped [`LUMP`] to an aggregate; (1) a group whose neighbours are all free starts an
/// aggregate of itself and them; (2) a free group joins the aggregate of a neighbour aggregated
/// in (1); (3) what is left starts aggregates with its free neighbours. Returns each group's
/// aggregate and their count.
pub(super) fn aggregate(a: &Blocks) -> (Vec<usize>, usize) {
    const FREE: usize = usize::MAX;
    let groups = a.rows();
    let mut of = vec![FREE; groups];
    let mut count = 0;
    let mut lumped = 0;
    for (k, agg) in of.iter_mut().enumerate() {
        if a.column[a.row(k)] == [k] {
            if lumped % LUMP == 0 {
                count += 1;
            }
            *agg = count - 1;
            lumped += 1;
        }
    }
    for k in 0..groups {
        let neighbours = &a.column[a.row(k)];
        if neighbours.iter().all(|&g| of[g] == FREE) {
            for &g in neighbours {
                of[g] = count;
            }
            count += 1;
        }
    }
    let first = of.clone();
    for (k, agg) in of.iter_mut().enumerate() {
        if *agg == FREE
            && let Some(&g) = a.column[a.row(k)].iter().find(|&&g| first[g] != FREE)
        {
            *agg = first[g];
        }
    }
    for k in 0..groups {
        if of[k] == FREE {
            for &g in &a.column[a.row(k)] {
                if of[g] == FREE {
                    of[g] = count;
                }
            }
            count += 1;
        }
    }
    (of, count)
}
