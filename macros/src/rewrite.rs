//! The user's function bodies with every read of a state field made explicit, so the runtime
//! can evaluate them at any state: shared by every model kind.
//!
//! `self.x` for a state field `x` becomes a hygienic local bound to the state being evaluated;
//! parameter reads (`self.k`) stay as they are. Any other use of `self` (a method call, passing
//! `self`, `self` inside a macro) is an error: it would read the struct's own, stale state.

use std::collections::BTreeMap;

use proc_macro2::{Span, TokenStream, TokenTree};
use quote::{ToTokens, format_ident};
use syn::visit_mut::{self, VisitMut};
use syn::{Block, Expr, Ident, Member};

use crate::errors::Errors;
use crate::model::{Model, Shape};
use crate::syntax::is_self;

/// The model's helper methods as the rewrite sees them: which names are methods taking `&self`
/// (implemented by [`crate::helpers::Helpers`], so this module does not depend on it).
pub(crate) trait Methods {
    /// Whether `name` is a helper taking `&self` (a call `self.name(…)` the rewrite keeps).
    fn is_method(&self, name: &Ident) -> bool;
}

/// The local a state field `x` is bound to inside a rewritten body.
pub(crate) fn state_local(field: &Ident) -> Ident {
    format_ident!("__odyn_{}", field, span = Span::mixed_site())
}

/// `block` with every `self.<state field>` of `model` replaced by the field's local, every other
/// use of `self` reported but calls of `helpers` taking `&self` (`self.restoring(self.x)`, whose
/// arguments are rewritten), and its transcendental calls routed through `odyn::math`
/// ([`crate::math`]); also the state fields read, with the tokens of the first read.
///
/// With `borrowed`, the locals of array and vector fields are references (`&[f64; N]`, so a call
/// copies no state) and a read becomes `(*local)`: indexing it copies one component, a method
/// call auto-references, a use by value copies as `self.x` did.
pub(crate) fn rewrite(
    block: &Block,
    model: &Model<'_>,
    helpers: &dyn Methods,
    function: &Ident,
    borrowed: bool,
    errors: &mut Errors,
) -> (Block, BTreeMap<String, TokenStream>) {
    let mut rewriter = Rewriter {
        model,
        helpers,
        function,
        borrowed,
        reads: BTreeMap::new(),
        errors,
    };
    let mut body = block.clone();
    rewriter.visit_block_mut(&mut body);
    crate::math::route_block(&mut body);
    (body, rewriter.reads)
}

/// Replaces `self.<state field>` with the field's local and rejects every other use of `self`.
struct Rewriter<'m, 'e> {
    model: &'m Model<'m>,
    helpers: &'m dyn Methods,
    function: &'m Ident,
    borrowed: bool,
    reads: BTreeMap<String, TokenStream>,
    errors: &'e mut Errors,
}

impl Rewriter<'_, '_> {
    fn reject_self(&mut self, span: Span, what: &str) {
        self.errors.at_span(
            span,
            format_args!(
                "{what} is not supported in `{}`: odyn evaluates it at states other than the \
                 struct's own, so `self` may only be read through its fields (`self.k`, `self.x`)",
                self.function
            ),
        );
    }
}

impl VisitMut for Rewriter<'_, '_> {
    fn visit_expr_mut(&mut self, expr: &mut Expr) {
        if let Expr::Field(field) = expr
            && is_self(&field.base)
        {
            if let Member::Named(name) = &field.member
                && let Some(state) = self.model.field(name)
            {
                self.reads
                    .entry(name.to_string())
                    .or_insert_with(|| field.to_token_stream());
                let local = state_local(state.ident);
                *expr = if self.borrowed && state.shape != Shape::Scalar {
                    syn::parse_quote_spanned!(name.span() => (*#local))
                } else {
                    syn::parse_quote_spanned!(name.span() => #local)
                };
            }
            return;
        }
        if let Expr::MethodCall(call) = expr
            && is_self(&call.receiver)
        {
            if self.helpers.is_method(&call.method) {
                for arg in &mut call.args {
                    self.visit_expr_mut(arg);
                }
                return;
            }
            let method = &call.method;
            self.errors.at_span(
                method.span(),
                format_args!(
                    "calling `self.{method}()` is not supported in `{}`: odyn evaluates it at \
                     states other than the struct's own, so `self` may only be read through its \
                     fields (`self.k`, `self.x`); to call a helper, write it in the model's \
                     `#[system]` impl block and mark it `#[odyn::function]` (it reads the state \
                     only through its arguments: `self.{method}(self.x)`)",
                    self.function
                ),
            );
            return;
        }
        if is_self(expr) {
            self.reject_self(span_of(expr), "using `self` other than to read a field");
            return;
        }
        visit_mut::visit_expr_mut(self, expr);
    }

    fn visit_macro_mut(&mut self, mac: &mut syn::Macro) {
        if let Some(span) = find_self(mac.tokens.clone()) {
            let name = mac
                .path
                .segments
                .last()
                .map(|s| s.ident.to_string())
                .unwrap_or_default();
            self.reject_self(span, &format!("`self` inside `{name}!`"));
        }
    }
}

fn span_of(expr: &Expr) -> Span {
    syn::spanned::Spanned::span(expr)
}

fn find_self(tokens: TokenStream) -> Option<Span> {
    tokens.into_iter().find_map(|tree| match tree {
        TokenTree::Ident(i) if i == "self" => Some(i.span()),
        TokenTree::Group(g) => find_self(g.stream()),
        _ => None,
    })
}
