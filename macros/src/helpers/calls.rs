//! Calls between helpers: which helper a call expression calls (`Self::f(…)`, `Model::f(…)`,
//! `self.f(…)`), and the cycles of helpers calling helpers, which inlining cannot end.

use proc_macro2::TokenStream;
use quote::ToTokens;
use syn::visit::{self, Visit};
use syn::{Expr, Ident, ImplItemFn};

use crate::errors::Errors;
use crate::syntax::is_self;

/// A call `Self::f(…)`, `Model::f(…)` or `self.f(…)`: the name, whether it was a method call on
/// `self`, and the arguments.
pub(super) fn call_of<'e>(
    e: &'e Expr,
    model: &Ident,
) -> Option<(
    String,
    bool,
    &'e syn::punctuated::Punctuated<Expr, syn::Token![,]>,
)> {
    match e {
        Expr::Call(c) => {
            let Expr::Path(p) = &*c.func else { return None };
            if p.qself.is_some() {
                return None;
            }
            let segments: Vec<&syn::PathSegment> = p.path.segments.iter().collect();
            match segments.as_slice() {
                [ty, f]
                    if p.path.leading_colon.is_none()
                        && (ty.ident == "Self" || ty.ident == *model)
                        && ty.arguments.is_none()
                        && f.arguments.is_none() =>
                {
                    Some((f.ident.to_string(), false, &c.args))
                }
                _ => None,
            }
        }
        Expr::MethodCall(m) if is_self(&m.receiver) && m.turbofish.is_none() => {
            Some((m.method.to_string(), true, &m.args))
        }
        _ => None,
    }
}

/// Reports each call that closes a cycle of helpers calling helpers (`f` calling `f`, or `f`
/// calling `g` calling `f`), at the call: inlining would never end.
///
/// `helpers` are the helpers' functions in order, `model` the model's name (`Model::f(…)`).
pub(super) fn recursion(model: &Ident, helpers: &[&ImplItemFn], errors: &mut Errors) {
    let calls: Vec<Vec<(usize, TokenStream)>> = helpers
        .iter()
        .map(|f| {
            let mut finder = Calls {
                model,
                helpers,
                found: Vec::new(),
            };
            finder.visit_block(&f.block);
            finder.found
        })
        .collect();
    // Depth-first from each helper in order: a call of a helper on the path is a back edge,
    // and every cycle has one. Each helper's calls are followed once.
    let n = calls.len();
    let mut done = vec![false; n];
    for start in 0..n {
        if done[start] {
            continue;
        }
        // (helper, its next call to follow)
        let mut stack: Vec<(usize, usize)> = vec![(start, 0)];
        while let Some(&(at, next)) = stack.last() {
            let Some((callee, tokens)) = calls[at].get(next) else {
                done[at] = true;
                stack.pop();
                continue;
            };
            if let Some(top) = stack.last_mut() {
                top.1 += 1;
            }
            let callee = *callee;
            if let Some(position) = stack.iter().position(|&(h, _)| h == callee) {
                let name = &helpers[callee].sig.ident;
                let through = if stack.len() - position > 1 {
                    let path: Vec<String> = stack[position..]
                        .iter()
                        .map(|&(h, _)| format!("`{}`", helpers[h].sig.ident))
                        .chain(std::iter::once(format!("`{name}`")))
                        .collect();
                    format!(" ({})", path.join(" → "))
                } else {
                    String::new()
                };
                errors.at(
                    tokens,
                    format_args!(
                        "`#[odyn::function]` `{name}` calls itself{through}: odyn \
                         differentiates a helper by inlining it into its caller, which for \
                         recursion never ends; write it without recursion"
                    ),
                );
            } else if !done[callee] {
                stack.push((callee, 0));
            }
        }
    }
}

/// The helper calls in a body: the callee's index and the call's tokens (the path or method
/// name).
struct Calls<'h> {
    model: &'h Ident,
    helpers: &'h [&'h ImplItemFn],
    found: Vec<(usize, TokenStream)>,
}

impl<'ast> Visit<'ast> for Calls<'_> {
    fn visit_expr(&mut self, e: &'ast Expr) {
        if let Some((name, _, _)) = call_of(e, self.model)
            && let Some(index) = self.helpers.iter().position(|f| f.sig.ident == name)
        {
            let tokens = match e {
                Expr::Call(c) => c.func.to_token_stream(),
                Expr::MethodCall(m) => m.method.to_token_stream(),
                other => other.to_token_stream(),
            };
            self.found.push((index, tokens));
        }
        visit::visit_expr(self, e);
    }
}
