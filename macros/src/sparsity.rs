//! Stage 5c: the Jacobian's structure without differentiating — which state components each
//! output can depend on — and a colouring of its columns for forward-mode evaluation.
//!
//! Models with many structural non-zeros (more than `generate::SYMBOLIC_LIMIT`) do not get one
//! expression per Jacobian entry: a dense 200-component model has 40 000 of them, and rustc
//! needed 52 s and 4.6 GB to compile that. They get one forward-mode tangent of the force instead, evaluated once
//! per column group: columns that share no row are seeded together (Curtis, Powell & Reid, "On
//! the estimation of sparse Jacobian matrices", IMA J. Appl. Math. 13, 1974), so a tridiagonal
//! Jacobian costs three evaluations whatever its size, a dense one n. The code emitted scales
//! with the size of the force's graph, not with the Jacobian's entries. Pure: no syn, no quote.

use crate::ir::{ExprId, Graph, Node};

/// For each output, the sorted state components it depends on: a superset of the derivative's
/// non-zeros (an entry that cancels, like ∂(x − x)/∂x, is kept). A `min`/`max` contributes the
/// dependencies of the value it picks, not of its comparison, matching its derivative.
pub(crate) fn pattern(g: &Graph, outputs: &[ExprId], components: usize) -> Vec<Vec<usize>> {
    let order = g.reachable(outputs.iter().copied());
    let mut deps: Vec<Vec<usize>> = vec![Vec::new(); order.last().map_or(0, |id| id.index() + 1)];
    for &id in &order {
        let set = match g.node(id) {
            Node::Var(k) if k < components => vec![k],
            Node::Pick {
                then, otherwise, ..
            } => union(&deps[then.index()], &deps[otherwise.index()]),
            node => node
                .children()
                .fold(Vec::new(), |set, child| union(&set, &deps[child.index()])),
        };
        deps[id.index()] = set;
    }
    outputs.iter().map(|f| deps[f.index()].clone()).collect()
}

/// The sorted union of two sorted lists.
fn union(a: &[usize], b: &[usize]) -> Vec<usize> {
    if a.is_empty() || a == b {
        return b.to_vec();
    }
    if b.is_empty() {
        return a.to_vec();
    }
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].cmp(&b[j]) {
            std::cmp::Ordering::Less => {
                out.push(a[i]);
                i += 1;
            }
            std::cmp::Ordering::Greater => {
                out.push(b[j]);
                j += 1;
            }
            std::cmp::Ordering::Equal => {
                out.push(a[i]);
                i += 1;
                j += 1;
            }
        }
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
    out
}

/// Groups of columns no two of which share a row, by greedy first-fit colouring in column order;
/// columns without non-zeros are in no group. When some row depends on every used column, each
/// column is its own group (no colouring can do better), found without the quadratic search.
pub(crate) fn column_groups(rows: &[Vec<usize>], components: usize) -> Vec<Vec<usize>> {
    let mut columns: Vec<Vec<usize>> = vec![Vec::new(); components];
    for (i, row) in rows.iter().enumerate() {
        for &j in row {
            columns[j].push(i);
        }
    }
    let used: Vec<usize> = (0..components)
        .filter(|&j| !columns[j].is_empty())
        .collect();
    if rows.iter().any(|row| row.len() == used.len()) {
        return used.into_iter().map(|j| vec![j]).collect();
    }
    // The groups already present in each row, and per group the last column that was refused it.
    let mut row_groups: Vec<Vec<usize>> = vec![Vec::new(); rows.len()];
    let mut refused_for: Vec<usize> = Vec::new();
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for j in used {
        for &i in &columns[j] {
            for &c in &row_groups[i] {
                refused_for[c] = j;
            }
        }
        let group = (0..groups.len())
            .find(|&c| refused_for[c] != j)
            .unwrap_or_else(|| {
                groups.push(Vec::new());
                refused_for.push(usize::MAX);
                groups.len() - 1
            });
        groups[group].push(j);
        for &i in &columns[j] {
            row_groups[i].push(group);
        }
    }
    groups
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tridiagonal pattern needs three groups at any size; a dense one n.
    #[test]
    fn groups_of_banded_and_dense_patterns() {
        let n: usize = 10;
        let tridiagonal: Vec<Vec<usize>> = (0..n)
            .map(|i| (i.saturating_sub(1)..(i + 2).min(n)).collect())
            .collect();
        let groups = column_groups(&tridiagonal, n);
        assert_eq!(groups.len(), 3);
        assert_eq!(groups[0], vec![0, 3, 6, 9]);
        let dense: Vec<Vec<usize>> = (0..n).map(|_| (0..n).collect()).collect();
        assert_eq!(column_groups(&dense, n).len(), n);
        // No two columns of a group share a row.
        for group in &groups {
            for row in &tridiagonal {
                assert!(group.iter().filter(|j| row.contains(j)).count() <= 1);
            }
        }
    }

    /// Dependencies follow the graph: y₀·y₁ depends on both, a parameter on neither, the time
    /// (variable 2, beyond the components) is not a column.
    #[test]
    fn pattern_follows_the_graph() {
        let mut g = Graph::default();
        let (y0, y1, t, p) = (g.var(0), g.var(1), g.var(2), g.opaque(0));
        let product = g.mul(y0, y1);
        let scaled = g.mul(p, t);
        let shifted = g.add(y1, scaled);
        let rows = pattern(&g, &[product, scaled, shifted], 2);
        assert_eq!(rows, vec![vec![0, 1], vec![], vec![1]]);
    }
}
