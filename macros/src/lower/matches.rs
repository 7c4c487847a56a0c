//! `match` and `if let` on the state (or a `match` whose guards read it), lowered as the `if`
//! chain they mean: `match s { p₁ if g₁ => a₁, p₂ => a₂, _ => a₃ }` is `{ let m = s; let
//! <names> = m; if test(p₁, m) && g₁ { a₁ } else if test(p₂, m) { a₂ } else { a₃ } }`, where
//! the test of a pattern on a number is comparisons: `_` and a name always match, a number or an
//! upper-case constant `c` is `m == c`, a range `a..b` is `m >= a && m < b` (`..=b`, `a..` and
//! the rest alike), and `p | q` is `test(p) || test(q)`. The last arm is the `else` (Rust's
//! exhaustiveness check guarantees it matches whatever the arms before it leave). The chain is
//! then an `if` on the state like any other ([`super::branches`]): each arm differentiated on
//! its own, the Jacobian the taken arm's, and on a boundary the arm Rust's comparison takes
//! there. Only the lowering reads the chain; the code that runs is the user's `match`.
//!
//! The names arms bind all alias the scrutinee, so they are bound once before the chain; an arm
//! that reads an outer local of a name another arm binds is refused rather than shadowed.

use proc_macro2::Span;
use quote::{ToTokens, format_ident};
use syn::{Expr, ExprMatch, Pat, RangeLimits, Stmt};

use super::Lowering;
use super::names::any_ident;

/// A `match` on the state as statements: the scrutinee and the arms' names bound, then the
/// `if` chain.
pub(super) struct Chain {
    pub(super) lets: Vec<Stmt>,
    pub(super) chain: Expr,
}

impl Chain {
    /// The chain as a block: `{ lets; chain }`.
    pub(super) fn block(self) -> syn::Block {
        let Chain { mut lets, chain } = self;
        match chain {
            // One arm: its statements follow the names.
            Expr::Block(b) => lets.extend(b.block.stmts),
            chain => lets.push(Stmt::Expr(chain, None)),
        }
        syn::Block {
            brace_token: Default::default(),
            stmts: lets,
        }
    }
}

impl Lowering<'_> {
    /// `e` as an `if` chain when it is a `match` (or an `if let`) whose scrutinee reads the
    /// state; `None` when it is not one. `after` are the statements that follow it in the same
    /// scope, which must not read the names the arms bind.
    pub(super) fn state_match(&self, e: &Expr, after: &[Stmt]) -> Option<syn::Result<Chain>> {
        let owned;
        let m = match e {
            Expr::Match(m) if self.depends(&m.expr) || self.guards_read_state(m) => m,
            Expr::If(i) => {
                let Expr::Let(l) = &*i.cond else { return None };
                if !self.depends(&l.expr) {
                    return None;
                }
                owned = if_let_as_match(i, l);
                &owned
            }
            _ => return None,
        };
        Some(self.chain(m, after))
    }

    fn guards_read_state(&self, m: &ExprMatch) -> bool {
        m.arms
            .iter()
            .any(|arm| arm.guard.as_ref().is_some_and(|(_, g)| self.depends(g)))
    }

    fn chain(&self, m: &ExprMatch, after: &[Stmt]) -> syn::Result<Chain> {
        let scrutinee = format_ident!("__odyn_scrutinee", span = Span::mixed_site());
        // Each arm's test and the names its pattern binds.
        let mut tests = Vec::with_capacity(m.arms.len());
        for arm in &m.arms {
            let mut bound = Vec::new();
            let test = pattern_test(&arm.pat, &scrutinee, &mut bound).map_err(|at| {
                self.error(
                    at,
                    "this pattern in a `match` on the state (a `match` or `if let` on a number, \
                     or with guards that read the state, takes `_`, a name, a number and ranges \
                     of numbers, `..0.0`, `0.0..=1.0`, joined by `|`, and guards of \
                     comparisons)",
                )
            })?;
            tests.push((test, bound));
        }
        // Every arm's names are bound before the chain: none may be read as an outer local by
        // an arm that does not bind it, the scrutinee, or the code after.
        let mut names: Vec<&syn::Ident> = Vec::new();
        for (arm, (_, bound)) in m.arms.iter().zip(&tests) {
            for name in bound {
                let read_elsewhere = m
                    .arms
                    .iter()
                    .zip(&tests)
                    .filter(|(other, (_, binds))| {
                        !std::ptr::eq(*other, arm) && !binds.contains(name)
                    })
                    .map(|(other, _)| other.to_token_stream())
                    .chain(std::iter::once(m.expr.to_token_stream()))
                    .chain(after.iter().map(ToTokens::to_token_stream))
                    .any(|tokens| any_ident(&tokens, &|i| i == name));
                if read_elsewhere {
                    return Err(self.refuse(
                        name,
                        format_args!(
                            "an arm of a `match` on the state binds `{name}`, a name that other \
                             code beside it reads as another value; odyn binds every arm's \
                             names before the arms, so rename `{name}` in this pattern"
                        ),
                    ));
                }
                if !names.contains(&name) {
                    names.push(name);
                }
            }
        }
        let arms: Vec<(Option<Expr>, syn::Block)> = m
            .arms
            .iter()
            .zip(&tests)
            .map(|(arm, (test, _))| {
                let test = match (&arm.guard, test) {
                    (Some((_, guard)), Some(test)) => Some(syn::parse_quote!((#test) && (#guard))),
                    (Some((_, guard)), None) => Some((**guard).clone()),
                    (None, test) => test.clone(),
                };
                let body = match &*arm.body {
                    Expr::Block(b) if b.label.is_none() => b.block.clone(),
                    body => syn::parse_quote!({ #body }),
                };
                (test, body)
            })
            .collect();
        let expr = &m.expr;
        let mut lets: Vec<Stmt> = vec![syn::parse_quote!(let #scrutinee = #expr;)];
        lets.extend(
            names
                .iter()
                .map(|n| -> Stmt { syn::parse_quote!(let #n = #scrutinee;) }),
        );
        // The last arm is the `else`; the arms before it test in order.
        let mut arms = arms.into_iter().rev();
        let Some((_, last)) = arms.next() else {
            return Err(self.error(m, "a `match` without arms"));
        };
        let mut chain = Expr::Block(syn::ExprBlock {
            attrs: Vec::new(),
            label: None,
            block: last,
        });
        for (test, body) in arms {
            let test = test.unwrap_or_else(|| syn::parse_quote!(true));
            // `else if …`, or `else { … }` for the last arm.
            chain = syn::parse_quote!(if #test #body else #chain);
        }
        Ok(Chain { lets, chain })
    }
}

/// `if let p = e { a } else { b }` as `match e { p => a, _ => b }`.
fn if_let_as_match(i: &syn::ExprIf, l: &syn::ExprLet) -> ExprMatch {
    let (pat, expr, then) = (&l.pat, &l.expr, &i.then_branch);
    let otherwise: Expr = match &i.else_branch {
        Some((_, e)) => (**e).clone(),
        None => syn::parse_quote!({}),
    };
    syn::parse_quote!(match #expr { #pat => #then, _ => #otherwise })
}

/// The test of pattern `pat` on the number `value`, as comparisons; `None` when it always
/// matches. The names it binds are pushed to `bound`. `Err` names the first part that is not
/// a pattern on a number.
fn pattern_test<'p>(
    pat: &'p Pat,
    value: &syn::Ident,
    bound: &mut Vec<syn::Ident>,
) -> Result<Option<Expr>, &'p Pat> {
    match pat {
        Pat::Wild(_) => Ok(None),
        Pat::Paren(p) => pattern_test(&p.pat, value, bound),
        // A constant, by Rust's naming convention (`MAX`): a number to compare with.
        Pat::Ident(p) if p.subpat.is_none() && starts_upper(&p.ident) => {
            let c = &p.ident;
            Ok(Some(syn::parse_quote!(#value == #c)))
        }
        Pat::Ident(p) if p.by_ref.is_none() => {
            bound.push(p.ident.clone());
            match &p.subpat {
                Some((_, sub)) => pattern_test(sub, value, bound),
                None => Ok(None),
            }
        }
        Pat::Lit(lit) => Ok(Some(syn::parse_quote!(#value == #lit))),
        Pat::Range(r) => {
            let low = r
                .start
                .as_ref()
                .map(|a| -> Expr { syn::parse_quote!(#value >= #a) });
            let high = r.end.as_ref().map(|b| -> Expr {
                match r.limits {
                    RangeLimits::HalfOpen(_) => syn::parse_quote!(#value < #b),
                    RangeLimits::Closed(_) => syn::parse_quote!(#value <= #b),
                }
            });
            Ok(match (low, high) {
                (Some(l), Some(h)) => Some(syn::parse_quote!(#l && #h)),
                (one, None) | (None, one) => one,
            })
        }
        Pat::Or(or) => {
            let mut tests = Vec::new();
            for case in &or.cases {
                match pattern_test(case, value, bound)? {
                    Some(test) => tests.push(test),
                    // One case always matches: so does the whole.
                    None => return Ok(None),
                }
            }
            Ok(Some(syn::parse_quote!(#((#tests))||*)))
        }
        other => Err(other),
    }
}

fn starts_upper(name: &syn::Ident) -> bool {
    name.to_string().starts_with(|c: char| c.is_uppercase())
}
