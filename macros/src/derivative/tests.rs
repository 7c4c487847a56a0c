use super::Differentiator;
use crate::ir::{Func, Func2, Graph, Node};

/// Central difference of `f` in variable `k`, for checking the rules.
fn central(g: &Graph, e: crate::ir::ExprId, vars: &[f64], k: usize) -> f64 {
    let h = 1e-6 * (1.0 + vars[k].abs());
    let (mut plus, mut minus) = (vars.to_vec(), vars.to_vec());
    plus[k] += h;
    minus[k] -= h;
    (g.eval(e, &plus, &[2.5]) - g.eval(e, &minus, &[2.5])) / (2.0 * h)
}

#[test]
fn every_rule_matches_central_differences() {
    let mut g = Graph::default();
    let (x, y, p) = (g.var(0), g.var(1), g.opaque(0));
    let mut cases = vec![];
    let xy = g.mul(x, y);
    cases.push(g.add(xy, p));
    cases.push(g.div(x, y));
    let sq = g.powi(x, 3);
    cases.push(g.sub(sq, y));
    cases.push(g.powf(y, p));
    for f in Func::ALL {
        // Scaled into (−1, 1) so asin and acos are defined at every test state.
        let product = g.mul(x, y);
        let quarter = g.num(0.25);
        let inner = g.mul(product, quarter);
        cases.push(g.call(f, inner));
    }
    for f in [Func2::Atan2, Func2::Hypot] {
        cases.push(g.call2(f, x, y));
    }
    // min(x, y) and max(x, y) away from the tie.
    cases.push(g.pick(x, y, x, y));
    cases.push(g.pick(y, x, x, y));
    let r = {
        let (x2, y2) = (g.powi(x, 2), g.powi(y, 2));
        let s = g.add(x2, y2);
        g.call(Func::Sqrt, s)
    };
    let r3 = g.powi(r, 3);
    cases.push(g.div(x, r3)); // the Kepler force
    let mut d = Differentiator::default();
    for &state in &[[0.7, 0.4], [1.3, -0.2], [-0.8, 0.9]] {
        for &case in &cases {
            for k in 0..2 {
                let derivative = d.derivative(&mut g, case, k);
                let exact = g.eval(derivative, &state, &[2.5]);
                let numeric = central(&g, case, &state, k);
                let scale = 1.0 + exact.abs();
                // Outside the function's domain (y^p at y < 0) there is nothing to compare.
                if numeric.is_nan() {
                    continue;
                }
                assert!(
                    (exact - numeric).abs() < 1e-6 * scale,
                    "{:?} ∂{k}: {exact} vs {numeric}",
                    g.node(case)
                );
            }
        }
    }
}

#[test]
fn constructors_fold_and_share() {
    let mut g = Graph::default();
    let x = g.var(0);
    let zero = g.num(0.0);
    let one = g.num(1.0);
    assert_eq!(g.add(zero, x), x);
    assert_eq!(g.mul(one, x), x);
    let product = g.mul(zero, x);
    assert!(g.is_zero(product));
    let nx = g.neg(x);
    assert_eq!(g.neg(nx), x);
    assert_eq!(g.powi(x, 1), x);
    let power = g.powi(x, 0);
    assert_eq!(g.constant(power), Some(1.0));
    let two = g.num(2.0);
    let three = g.num(3.0);
    let sum = g.add(two, three);
    assert_eq!(g.constant(sum), Some(5.0));
    // Hash-consing: x·2 and 2·x are one node.
    let a = g.mul(x, two);
    let b = g.mul(two, x);
    assert_eq!(a, b);
    let before = g.len();
    let c = g.mul(x, two);
    assert_eq!((c, g.len()), (a, before));
    // −0 and +0 are one constant.
    assert_eq!(g.num(-0.0), zero);
}

#[test]
fn derivatives_simplify_as_they_are_built() {
    let mut g = Graph::default();
    let (x, y) = (g.var(0), g.var(1));
    let k = g.opaque(0);
    let kx = g.mul(k, x);
    let f = g.neg(kx); // −k·x
    let mut d = Differentiator::default();
    let dx = d.derivative(&mut g, f, 0);
    assert_eq!(g.node(dx), Node::Neg(k));
    let dy = d.derivative(&mut g, f, 1);
    assert!(g.is_zero(dy));
    // ∂ sin(y)/∂y reuses y.
    let s = g.call(Func::Sin, y);
    let ds = d.derivative(&mut g, s, 1);
    assert_eq!(g.node(ds), Node::Call(Func::Cos, y));
}
