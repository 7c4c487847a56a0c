//! Conditions on the state (`if x > 0.0 && self.on`): which are supported, and how they become
//! comparisons in the graph ([`crate::ir::Node::Pick`]) that choose a branch's arm.

use syn::{BinOp, Expr};

use super::Lowering;
use crate::ir::ExprId;

/// A condition on the state, lowered.
pub(super) enum Condition {
    /// `a <= b`, or, `negated`, its negation.
    Compare {
        a: ExprId,
        b: ExprId,
        negated: bool,
    },
    Not(Box<Condition>),
    And(Box<Condition>, Box<Condition>),
    Or(Box<Condition>, Box<Condition>),
}

impl Lowering<'_> {
    /// The conditions of an `if` on the state, lowered in the scope before its arms.
    pub(super) fn conditions(&mut self, conditions: &[Expr]) -> syn::Result<Vec<Condition>> {
        let mut lowered = Vec::with_capacity(conditions.len());
        for (k, c) in conditions.iter().enumerate() {
            // An `else if`'s condition runs only when those before it failed.
            lowered.push(self.conditionally(k > 0, |l| l.condition(c))?);
        }
        Ok(lowered)
    }

    /// `lower`, counted as inside an arm when `conditional` (code that runs only in some runs:
    /// an index past an end there does not cap a loop bounded at run time; see
    /// [`Lowering::component`]).
    fn conditionally<T>(&mut self, conditional: bool, lower: impl FnOnce(&mut Self) -> T) -> T {
        self.arms += u32::from(conditional);
        let result = lower(self);
        self.arms -= u32::from(conditional);
        result
    }

    /// Checks that `condition` is comparisons (`<`, `<=`, `>`, `>=`, `==`, `!=`) and parameter-only
    /// conditions joined by `&&`, `||` and `!`, in parentheses or not; on failure, the first part
    /// that is not.
    pub(super) fn check_condition<'e>(&self, condition: &'e Expr) -> Result<(), &'e Expr> {
        match condition {
            Expr::Paren(p) => self.check_condition(&p.expr),
            Expr::Group(g) => self.check_condition(&g.expr),
            Expr::Unary(u) if matches!(u.op, syn::UnOp::Not(_)) => self.check_condition(&u.expr),
            Expr::Binary(b) if matches!(b.op, BinOp::And(_) | BinOp::Or(_)) => {
                self.check_condition(&b.left)?;
                self.check_condition(&b.right)
            }
            Expr::Binary(b)
                if matches!(
                    b.op,
                    BinOp::Lt(_)
                        | BinOp::Le(_)
                        | BinOp::Gt(_)
                        | BinOp::Ge(_)
                        | BinOp::Eq(_)
                        | BinOp::Ne(_)
                ) =>
            {
                Ok(())
            }
            // `if let` binds names the arm reads: not a flag.
            other if !matches!(other, Expr::Let(_)) && !self.depends(other) => Ok(()),
            other => Err(other),
        }
    }

    fn condition(&mut self, condition: &Expr) -> syn::Result<Condition> {
        match condition {
            Expr::Paren(p) => self.condition(&p.expr),
            Expr::Group(g) => self.condition(&g.expr),
            Expr::Unary(u) if matches!(u.op, syn::UnOp::Not(_)) => {
                Ok(Condition::Not(Box::new(self.condition(&u.expr)?)))
            }
            Expr::Binary(b) if matches!(b.op, BinOp::And(_) | BinOp::Or(_)) => {
                // The right side runs only when the left does not decide.
                let l = Box::new(self.condition(&b.left)?);
                let r = Box::new(self.conditionally(true, |l| l.condition(&b.right))?);
                Ok(match b.op {
                    BinOp::And(_) => Condition::And(l, r),
                    _ => Condition::Or(l, r),
                })
            }
            // A parameter-only condition (a flag, a call), as 1 or 0 computed with the opaque
            // values: taken when ½ ≤ it.
            other if !matches!(other, Expr::Let(_)) && !self.depends(other) => {
                let flag = self.opaque(quote::quote!(if #other { 1.0 } else { 0.0 }));
                let half = self.graph.num(0.5);
                Ok(Condition::Compare {
                    a: half,
                    b: flag,
                    negated: false,
                })
            }
            // `l == r` is `l <= r && r <= l`; `l != r` its negation.
            Expr::Binary(b) if matches!(b.op, BinOp::Eq(_) | BinOp::Ne(_)) => {
                let (left, right) = (self.scalar(&b.left)?, self.scalar(&b.right)?);
                let compare = |a, b| {
                    Box::new(Condition::Compare {
                        a,
                        b,
                        negated: false,
                    })
                };
                let equal = Condition::And(compare(left, right), compare(right, left));
                Ok(match b.op {
                    BinOp::Eq(_) => equal,
                    _ => Condition::Not(Box::new(equal)),
                })
            }
            Expr::Binary(b) => {
                let (left, right) = (self.scalar(&b.left)?, self.scalar(&b.right)?);
                // `l <= r` as is; `l < r` is `!(r <= l)`; `l >= r` is `r <= l`; `l > r` is
                // `!(l <= r)` (the same for every number but NaN, where no branch is meaningful).
                let (a, b, negated) = match b.op {
                    BinOp::Le(_) => (left, right, false),
                    BinOp::Lt(_) => (right, left, true),
                    BinOp::Ge(_) => (right, left, false),
                    _ => (left, right, true),
                };
                Ok(Condition::Compare { a, b, negated })
            }
            other => Err(self.error(other, "this condition on the state")),
        }
    }

    /// `then` where `condition` holds, else `otherwise`: `a && b` is `a` then `b`, `a || b`
    /// is `a` else `b` (both sides evaluated; they are values without effects).
    pub(super) fn when(
        &mut self,
        condition: &Condition,
        then: ExprId,
        otherwise: ExprId,
    ) -> ExprId {
        match condition {
            &Condition::Compare { a, b, negated } => {
                if negated {
                    self.graph.pick(a, b, otherwise, then)
                } else {
                    self.graph.pick(a, b, then, otherwise)
                }
            }
            Condition::Not(c) => self.when(c, otherwise, then),
            Condition::And(l, r) => {
                let inner = self.when(r, then, otherwise);
                self.when(l, inner, otherwise)
            }
            Condition::Or(l, r) => {
                let inner = self.when(r, then, otherwise);
                self.when(l, then, inner)
            }
        }
    }
}
