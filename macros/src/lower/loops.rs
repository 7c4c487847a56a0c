//! Loops whose body reads the state, unrolled: `for k in a..b` (or `a..=b`) whose bounds, and
//! `while cond` whose condition, odyn evaluates at compile time (integer literals, and locals
//! computed from them, such as a counter `i` of `let mut i = 0; … i += 1;`).
//!
//! Each iteration's body is lowered in a scope of its own, the loop variable bound to the
//! iteration's number (so `self.x[k]` names a component); its state-free code goes to the
//! prologue in a block of its own that starts by binding the loop variable, in order, so the
//! prologue changes the locals the loop changes as the loop does.

use std::collections::HashMap;

use syn::visit::{self, Visit};
use syn::{BinOp, Expr, ExprForLoop, ExprWhile, Lit, RangeLimits, UnOp};

use super::statements::Context;
use super::{Branch, BranchKind, Lowering, Prologue, Value};

/// Most iterations the lowering of one function unrolls, all loops together: enough for a loop
/// over the components of any state odyn differentiates symbolically, few enough that a typo
/// (`0..100000`) is an error, not a compiler that runs out of memory.
pub(super) const MAX_ITERATIONS: usize = 4096;

/// The integer types a known integer may be cast to in an index (`k as usize`).
const INTEGER_TYPES: [&str; 10] = [
    "usize", "isize", "u8", "u16", "u32", "u64", "i8", "i16", "i32", "i64",
];

impl Lowering<'_> {
    /// The integer a state-free expression evaluates to at compile time: a literal, or a local
    /// computed from literals (a loop variable, a counter).
    pub(super) fn known_integer(&mut self, e: &Expr) -> Option<i64> {
        if let Expr::Lit(syn::ExprLit {
            lit: Lit::Int(i), ..
        }) = e
        {
            return i.base10_parse().ok();
        }
        if self.depends(e) {
            return None;
        }
        // Integer-only arithmetic the graph of numbers does not express (`(i + 1) % n`).
        if let Expr::Binary(b) = e
            && matches!(b.op, BinOp::Rem(_))
        {
            let (l, r) = (self.known_integer(&b.left)?, self.known_integer(&b.right)?);
            return l.checked_rem(r);
        }
        if let Expr::Paren(p) = e {
            return self.known_integer(&p.expr);
        }
        // `k as usize` of an integer loop variable or counter.
        if let Expr::Cast(c) = e
            && INTEGER_TYPES
                .iter()
                .any(|t| crate::syntax::is_plain(&c.ty, t))
        {
            return self.known_integer(&c.expr);
        }
        let prologue = self.prologue.len();
        let value = self.expr(e).ok();
        // Whatever the attempt made opaque is not read.
        self.prologue.truncate(prologue);
        match value {
            Some(Value::Scalar(id)) => self
                .graph
                .constant(id)
                .filter(|v| v.fract() == 0.0 && v.abs() < 2f64.powi(53))
                .map(|v| v as i64),
            _ => None,
        }
    }

    /// An index: an integer literal or a known integer (`self.x[k]` in an unrolled loop).
    pub(super) fn known_index(&mut self, e: &Expr) -> Option<usize> {
        crate::syntax::int_literal(e)
            .or_else(|| self.known_integer(e).and_then(|i| usize::try_from(i).ok()))
    }

    /// A `for` loop whose body reads the state, unrolled.
    pub(super) fn unroll_for(&mut self, l: &ExprForLoop) -> syn::Result<()> {
        self.no_jumps(&l.body)?;
        let name = match &*l.pat {
            syn::Pat::Ident(p) if p.subpat.is_none() && p.by_ref.is_none() => Some(&p.ident),
            syn::Pat::Wild(_) => None,
            other => {
                return Err(self.error(
                    other,
                    "a loop pattern other than a name or `_` in a loop on the state",
                ));
            }
        };
        let bounds = match &*l.expr {
            Expr::Range(r) => match (&r.start, &r.end) {
                (Some(start), Some(end)) => {
                    let (a, b) = (self.known_integer(start), self.known_integer(end));
                    a.zip(b).map(|(a, b)| match r.limits {
                        RangeLimits::HalfOpen(_) => (a, b),
                        RangeLimits::Closed(_) => (a, b.saturating_add(1)),
                    })
                }
                _ => None,
            },
            _ => None,
        };
        let Some((start, end)) = bounds else {
            return self.guarded_for(l, name);
        };
        let count = usize::try_from(end.saturating_sub(start)).unwrap_or(0);
        self.count_iterations(count, &l.expr)?;
        for k in start..end {
            let literal = proc_macro2::Literal::i64_unsuffixed(k);
            let bind = name.map(|n| {
                let stmt: syn::Stmt = syn::parse_quote!(let #n = #literal;);
                (n.to_string(), stmt)
            });
            let value = Value::Scalar(self.graph.num(k as f64));
            self.iteration(&l.body, bind.map(|(n, stmt)| (n, value, stmt)))?;
        }
        Ok(())
    }

    /// A `while` loop whose body reads the state, unrolled while its condition, evaluated at
    /// compile time, holds.
    pub(super) fn unroll_while(&mut self, w: &ExprWhile) -> syn::Result<()> {
        self.no_jumps(&w.body)?;
        loop {
            match self.known_condition(&w.cond) {
                None => return self.guarded_while(w),
                Some(false) => return Ok(()),
                Some(true) => {
                    self.count_iterations(1, &w.cond)?;
                    self.iteration(&w.body, None)?;
                }
            }
        }
    }

    /// One iteration: the body in a scope of its own (with the loop variable, if any), its
    /// prologue in a block of its own.
    pub(super) fn iteration(
        &mut self,
        body: &syn::Block,
        variable: Option<(String, Value, syn::Stmt)>,
    ) -> syn::Result<()> {
        let outer = std::mem::take(&mut self.prologue);
        self.scopes.push(HashMap::new());
        if let Some((name, value, stmt)) = variable {
            self.prologue.push(Prologue::Stmt(Box::new(stmt)));
            self.bind(name, Some(value), false);
        }
        let result = self.run(&body.stmts, Context::Arm);
        self.scopes.pop();
        let own = std::mem::replace(&mut self.prologue, outer);
        result?;
        // A block of the prologue, which `changes_outer` looks into (the loop's changes to the
        // function's locals are the function's).
        self.prologue.push(Prologue::Branch(Box::new(Branch {
            selector: u32::MAX,
            kind: BranchKind::Every,
            arms: vec![own],
        })));
        Ok(())
    }

    pub(super) fn count_iterations(&mut self, count: usize, at: &Expr) -> syn::Result<()> {
        self.iterations = self.iterations.saturating_add(count);
        if self.iterations > MAX_ITERATIONS {
            return Err(self.refuse(
                at,
                format_args!(
                    "loops on the state that run more than {MAX_ITERATIONS} times in all (odyn \
                     unrolls them to differentiate them)"
                ),
            ));
        }
        Ok(())
    }

    /// The refusal of a `for` on the state that is not over `a..end` (or `a..=end`) with a start
    /// known at compile time.
    pub(super) fn unknown_bound(&self, at: &Expr) -> syn::Error {
        self.error(
            at,
            "a loop whose body reads the state and whose range odyn cannot unroll (`for`; odyn \
             unrolls a loop on the state, so it must run over a range whose start is an integer \
             literal or a local computed from them and whose end is one too or reads only \
             parameters: `for k in 0..3`, `for k in 1..self.n`)",
        )
    }

    /// The value of a loop condition at compile time: comparisons of known integers joined by
    /// `&&`, `||` and `!`.
    pub(super) fn known_condition(&mut self, e: &Expr) -> Option<bool> {
        match e {
            Expr::Paren(p) => self.known_condition(&p.expr),
            Expr::Group(g) => self.known_condition(&g.expr),
            Expr::Lit(syn::ExprLit {
                lit: Lit::Bool(b), ..
            }) => Some(b.value),
            Expr::Unary(u) if matches!(u.op, UnOp::Not(_)) => {
                self.known_condition(&u.expr).map(|b| !b)
            }
            Expr::Binary(b) => match b.op {
                BinOp::And(_) => match self.known_condition(&b.left)? {
                    false => Some(false),
                    true => self.known_condition(&b.right),
                },
                BinOp::Or(_) => match self.known_condition(&b.left)? {
                    true => Some(true),
                    false => self.known_condition(&b.right),
                },
                op => {
                    let (l, r) = (self.known_integer(&b.left)?, self.known_integer(&b.right)?);
                    match op {
                        BinOp::Lt(_) => Some(l < r),
                        BinOp::Le(_) => Some(l <= r),
                        BinOp::Gt(_) => Some(l > r),
                        BinOp::Ge(_) => Some(l >= r),
                        BinOp::Eq(_) => Some(l == r),
                        BinOp::Ne(_) => Some(l != r),
                        _ => None,
                    }
                }
            },
            _ => None,
        }
    }

    /// Refuses `break` and `continue` in a loop to unroll.
    fn no_jumps(&self, body: &syn::Block) -> syn::Result<()> {
        #[derive(Default)]
        struct Jumps(Option<proc_macro2::TokenStream>);
        impl<'ast> Visit<'ast> for Jumps {
            fn visit_expr(&mut self, e: &'ast Expr) {
                if self.0.is_some() {
                    return;
                }
                match e {
                    Expr::Break(b) => self.0 = Some(quote::ToTokens::to_token_stream(b)),
                    Expr::Continue(c) => self.0 = Some(quote::ToTokens::to_token_stream(c)),
                    Expr::Closure(_) | Expr::Async(_) => {}
                    _ => visit::visit_expr(self, e),
                }
            }
            fn visit_item(&mut self, _: &'ast syn::Item) {}
        }
        let mut jumps = Jumps::default();
        jumps.visit_block(body);
        match jumps.0 {
            Some(at) => Err(self.error(at, "`break` or `continue` in a loop on the state")),
            None => Ok(()),
        }
    }
}
