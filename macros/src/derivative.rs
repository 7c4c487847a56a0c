//! Stage 5b: exact differentiation of the expression graph, ∂e/∂yₖ (and ∂e/∂t, the time being
//! one more variable; ∂e/∂p through a parameter's opaque reads), by the chain rule.
//!
//! Functions with kinks are differentiated almost everywhere, and at the kink take the
//! derivative of the side Rust's own definition falls on: |x|′ = signum(x), which is ±1 at ±0;
//! min(a, b)′ = a′ where a ≤ b (so a′ at a tie), max(a, b)′ = a′ where a ≥ b; signum′ = 0. A branch
//! on parameters differentiates the branch taken. A call of a function the graph cannot see into
//! ([`Node::Extern`]) is the one inexact rule: its partial derivatives are central differences of
//! the call itself ([`Node::Slope`]), the chain rule around them exact.
//!
//! Every rule builds its result with the graph's smart constructors, so derivatives simplify as
//! they are made and reuse the nodes of the function itself (∂ sin u = cos u · ∂u shares u;
//! ∂√u = ∂u / (2√u) shares √u). Results are memoised per (node, variable). Pure: no syn, no quote.

use std::collections::HashMap;

use crate::ir::{ExprId, Func, Func2, Graph, Node};

/// Differentiates expressions of one graph, remembering what it has done.
#[derive(Default)]
pub(crate) struct Differentiator {
    memo: HashMap<(ExprId, Wrt), ExprId>,
}

/// What a derivative is taken with respect to.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
enum Wrt {
    /// One variable: ∂e/∂yₖ.
    Var(usize),
    /// The directional derivative Σₖ ∂e/∂yₖ·sₖ along a seed vector s, whose components are the
    /// graph's variables `first_seed + k` for the state components k < `components`.
    Direction {
        first_seed: usize,
        components: usize,
    },
    /// One opaque value: ∂e/∂(opaque `index`), a parameter's read (`self.k`) for ∂f/∂p.
    Opaque(usize),
}

impl Differentiator {
    /// ∂`e`/∂(variable `var`): a state component, or the time.
    pub(crate) fn derivative(&mut self, g: &mut Graph, e: ExprId, var: usize) -> ExprId {
        self.differentiate(g, e, Wrt::Var(var))
    }

    /// ∂`e`/∂(opaque value `index`): with respect to one read of a parameter.
    pub(crate) fn derivative_by_opaque(
        &mut self,
        g: &mut Graph,
        e: ExprId,
        index: usize,
    ) -> ExprId {
        self.differentiate(g, e, Wrt::Opaque(index))
    }

    /// The forward-mode tangent of `e`, Σₖ ∂e/∂yₖ·sₖ, where the seed sₖ of state component
    /// k < `components` is the graph's variable `first_seed + k` (the time is not seeded). One
    /// tangent of each output gives a whole column group of the Jacobian per evaluation.
    pub(crate) fn tangent(
        &mut self,
        g: &mut Graph,
        e: ExprId,
        first_seed: usize,
        components: usize,
    ) -> ExprId {
        self.differentiate(
            g,
            e,
            Wrt::Direction {
                first_seed,
                components,
            },
        )
    }

    fn differentiate(&mut self, g: &mut Graph, e: ExprId, var: Wrt) -> ExprId {
        if let Some(&d) = self.memo.get(&(e, var)) {
            return d;
        }
        let d = match g.node(e) {
            Node::Opaque(k) => g.num(if var == Wrt::Opaque(k) { 1.0 } else { 0.0 }),
            Node::Const(_) => g.num(0.0),
            Node::Var(k) => match var {
                Wrt::Var(v) => g.num(if k == v { 1.0 } else { 0.0 }),
                Wrt::Opaque(_) => g.num(0.0),
                Wrt::Direction {
                    first_seed,
                    components,
                } if k < components => g.var(first_seed + k),
                Wrt::Direction { .. } => g.num(0.0),
            },
            Node::Add(a, b) => {
                let (da, db) = (self.differentiate(g, a, var), self.differentiate(g, b, var));
                g.add(da, db)
            }
            Node::Neg(a) => {
                let da = self.differentiate(g, a, var);
                g.neg(da)
            }
            Node::Mul(a, b) => {
                // (ab)′ = a′b + ab′
                let (da, db) = (self.differentiate(g, a, var), self.differentiate(g, b, var));
                let (left, right) = (g.mul(da, b), g.mul(a, db));
                g.add(left, right)
            }
            Node::Div(a, b) => {
                // (a/b)′ = a′/b − (a/b)·b′/b, reusing the quotient node e = a/b.
                let (da, db) = (self.differentiate(g, a, var), self.differentiate(g, b, var));
                let first = g.div(da, b);
                let ratio = g.div(db, b);
                let second = g.mul(e, ratio);
                g.sub(first, second)
            }
            Node::Powi(a, n) => {
                // (aⁿ)′ = n·aⁿ⁻¹·a′
                let da = self.differentiate(g, a, var);
                let n_f = g.num(f64::from(n));
                let lower = g.powi(a, n - 1);
                let scaled = g.mul(n_f, lower);
                g.mul(scaled, da)
            }
            Node::Powf(a, b) => {
                // (aᵇ)′ = b·aᵇ⁻¹·a′ + aᵇ·ln a·b′. The lowering keeps b free of the state, so b′
                // is zero but with respect to a parameter (∂f/∂p).
                let (da, db) = (self.differentiate(g, a, var), self.differentiate(g, b, var));
                let one = g.num(1.0);
                let b_minus_one = g.sub(b, one);
                let lower = g.powf(a, b_minus_one);
                let scaled = g.mul(b, lower);
                let by_base = g.mul(scaled, da);
                if g.is_zero(db) {
                    by_base
                } else {
                    let ln_a = g.call(Func::Ln, a);
                    let by_exponent = g.mul(e, ln_a);
                    let by_exponent = g.mul(by_exponent, db);
                    g.add(by_base, by_exponent)
                }
            }
            Node::Call(f, a) => {
                let da = self.differentiate(g, a, var);
                if g.is_zero(da) {
                    da
                } else {
                    let outer = self.outer(g, f, a, e);
                    g.mul(outer, da)
                }
            }
            Node::Call2(f, a, b) => {
                let (da, db) = (self.differentiate(g, a, var), self.differentiate(g, b, var));
                match f {
                    // atan2(a, b)′ = (b·a′ − a·b′)/(a² + b²), as ((b/h)·a′ − (a/h)·b′)/h with
                    // h = hypot(a, b): a² + b² overflows at 1e155 and underflows at 1e-162.
                    Func2::Atan2 => {
                        let h = g.call2(Func2::Hypot, a, b);
                        let (b_h, a_h) = (g.div(b, h), g.div(a, h));
                        let (p, q) = (g.mul(b_h, da), g.mul(a_h, db));
                        let numerator = g.sub(p, q);
                        g.div(numerator, h)
                    }
                    // hypot(a, b)′ = (a·a′ + b·b′)/hypot(a, b), reusing the node e.
                    Func2::Hypot => {
                        let (p, q) = (g.mul(a, da), g.mul(b, db));
                        let numerator = g.add(p, q);
                        g.div(numerator, e)
                    }
                }
            }
            Node::Select {
                selector,
                arm,
                then,
                otherwise,
            } => {
                let (dt, de) = (
                    self.differentiate(g, then, var),
                    self.differentiate(g, otherwise, var),
                );
                g.select(selector, arm, dt, de)
            }
            Node::Pick {
                a,
                b,
                then,
                otherwise,
            } => {
                let (dt, de) = (
                    self.differentiate(g, then, var),
                    self.differentiate(g, otherwise, var),
                );
                g.pick(a, b, dt, de)
            }
            Node::Extern { args, arity, .. } => {
                // Σᵢ ∂f/∂aᵢ · aᵢ′, each ∂f/∂aᵢ a central difference of the call.
                let mut sum = g.num(0.0);
                for (i, &a) in args[..usize::from(arity)].iter().enumerate() {
                    let da = self.differentiate(g, a, var);
                    if !g.is_zero(da) {
                        let slope = g.slope(e, u8::try_from(i).expect("at most four"));
                        let term = g.mul(slope, da);
                        sum = g.add(sum, term);
                    }
                }
                sum
            }
            // No second derivatives are taken (the Jacobian, ∂f/∂t, ∂f/∂p and tangents are all
            // first derivatives of f); were one asked for, NaN would surface at run time rather
            // than a silent zero.
            Node::Slope { .. } => g.num(f64::NAN),
        };
        self.memo.insert((e, var), d);
        d
    }

    /// f′(a) for f(a) = `e`.
    fn outer(&mut self, g: &mut Graph, f: Func, a: ExprId, e: ExprId) -> ExprId {
        match f {
            Func::Sqrt => {
                // 1 / (2√a)
                let two = g.num(2.0);
                let denominator = g.mul(two, e);
                let one = g.num(1.0);
                g.div(one, denominator)
            }
            Func::Cbrt => {
                // 1 / (3·∛a²)
                let three = g.num(3.0);
                let square = g.powi(e, 2);
                let denominator = g.mul(three, square);
                let one = g.num(1.0);
                g.div(one, denominator)
            }
            Func::Exp => e,
            Func::Exp2 => {
                let ln2 = g.num(std::f64::consts::LN_2);
                g.mul(ln2, e)
            }
            Func::ExpM1 => {
                let one = g.num(1.0);
                g.add(e, one)
            }
            Func::Ln => {
                let one = g.num(1.0);
                g.div(one, a)
            }
            Func::Ln1p => {
                let one = g.num(1.0);
                let denominator = g.add(one, a);
                g.div(one, denominator)
            }
            Func::Log2 | Func::Log10 => {
                let ln_base = g.num(if f == Func::Log2 {
                    std::f64::consts::LN_2
                } else {
                    std::f64::consts::LN_10
                });
                let denominator = g.mul(ln_base, a);
                let one = g.num(1.0);
                g.div(one, denominator)
            }
            Func::Asin | Func::Acos => {
                // ±1/√(1 − a²)
                let one = g.num(1.0);
                let square = g.powi(a, 2);
                let rest = g.sub(one, square);
                let root = g.call(Func::Sqrt, rest);
                let inverse = g.div(one, root);
                if f == Func::Asin {
                    inverse
                } else {
                    g.neg(inverse)
                }
            }
            Func::Atan => {
                let one = g.num(1.0);
                let square = g.powi(a, 2);
                let denominator = g.add(one, square);
                g.div(one, denominator)
            }
            Func::Sinh => g.call(Func::Cosh, a),
            Func::Cosh => g.call(Func::Sinh, a),
            Func::Sin => g.call(Func::Cos, a),
            Func::Cos => {
                let sin = g.call(Func::Sin, a);
                g.neg(sin)
            }
            Func::Tan => {
                // 1 + tan²a
                let one = g.num(1.0);
                let square = g.powi(e, 2);
                g.add(one, square)
            }
            Func::Tanh => {
                // 1 − tanh²a
                let one = g.num(1.0);
                let square = g.powi(e, 2);
                g.sub(one, square)
            }
            // |a|′ = signum(a): ±1 at ±0, as Rust defines `signum`.
            Func::Abs => g.call(Func::Signum, a),
            Func::Signum => g.num(0.0),
        }
    }
}

#[cfg(test)]
mod tests;
