//! Calls of the model's helper functions ([`crate::helpers`]): the helper's body is lowered in a
//! scope of its own, its parameters bound to the arguments' values, so the call's value is the
//! helper's expression of its arguments in the graph and differentiation needs no rule of its
//! own.
//!
//! The helper's state-free code (its `let`s of parameters, its opaque values, its branches on
//! parameters) goes to the prologue in a block of its own, [`Prologue::Scope`], which starts by
//! binding the parameters whose arguments do not read the state to those arguments: the helper's
//! names are its own there as in its body, and cannot shadow its caller's. A parameter bound to
//! the state is never read by prologue code (code that reads it depends on the state).

use std::collections::HashMap;

use quote::{ToTokens, quote};
use syn::Expr;

use super::{Lowering, Prologue, Value};
use crate::helpers::{Output, Param};
use crate::model::Shape;

/// Whether `value` has the shape of `shape`.
fn fits(value: &Value, shape: Shape) -> bool {
    match (value, shape) {
        (Value::Scalar(_), Shape::Scalar) => true,
        (Value::Vector(v), Shape::Array(n) | Shape::Vector(n)) => v.len() == n.count(),
        (Value::Rows(rows), Shape::Rows(n, row)) => {
            rows.len() == n.count() && rows.iter().all(|r| r.len() == row.len())
        }
        _ => false,
    }
}

/// Whether `value` has the shape of the helper's return type.
fn fits_output(value: &Value, output: &Output) -> bool {
    match (value, output) {
        (_, Output::One(shape)) => fits(value, *shape),
        (Value::Tuple(parts), Output::Tuple(shapes)) => {
            parts.len() == shapes.len() && parts.iter().zip(shapes).all(|(v, s)| fits(v, *s))
        }
        _ => false,
    }
}

/// The state the lowering of a helper's body replaces, restored after it.
struct Caller {
    scopes: super::scope::Scopes,
    prologue: Vec<Prologue>,
    time_in_scope: bool,
}

impl Lowering<'_> {
    /// The value of `e`, a call of a helper ([`crate::helpers::Helpers::called`]).
    pub(super) fn inline_call(&mut self, e: &Expr) -> syn::Result<Value> {
        let helpers = self.helpers;
        let Some((helper, args)) = helpers.called(e) else {
            return Err(self.error(e, "a call"));
        };
        let at = match e {
            Expr::Call(c) => c.func.to_token_stream(),
            Expr::MethodCall(m) => m.method.to_token_stream(),
            other => other.to_token_stream(),
        };
        let name = helper.f.sig.ident.to_string();
        if self.inlining.contains(&name) {
            return Err(self.refuse(
                at,
                format_args!(
                    "`#[odyn::function]` `{name}` calls itself: odyn differentiates a helper by \
                     inlining it into its caller, which for recursion never ends"
                ),
            ));
        }
        if args.len() != helper.params.len() {
            return Err(self.refuse(
                at,
                format_args!(
                    "`{name}` takes {} arguments, not {}",
                    helper.params.len(),
                    args.len()
                ),
            ));
        }
        // The arguments, in the caller's scope.
        let mut bound: Vec<(&Param, Value, bool, &Expr)> = Vec::with_capacity(args.len());
        for (param, arg) in helper.params.iter().zip(args) {
            let dependent = self.depends(arg);
            let value = self.expr(arg)?;
            if !fits(&value, param.shape) {
                return Err(self.refuse(
                    arg,
                    format_args!(
                        "an argument that is not a `{}`, the type of `{name}`'s parameter `{}`,",
                        param.ty.to_token_stream(),
                        param.pat.to_token_stream()
                    ),
                ));
            }
            bound.push((param, value, dependent, arg));
        }
        // The helper's own scope: its parameters, and no name of the caller's.
        let caller = Caller {
            scopes: std::mem::replace(&mut self.scopes, vec![HashMap::new()]),
            prologue: std::mem::take(&mut self.prologue),
            time_in_scope: std::mem::replace(&mut self.time_in_scope, false),
        };
        self.inlining.push(name);
        let state_free: Vec<&(&Param, Value, bool, &Expr)> = bound
            .iter()
            .filter(|(_, _, dependent, _)| !dependent)
            .collect();
        // One `let` for all, so an argument naming a caller's local that a parameter shares its
        // name with reads the caller's; emitted only when the helper leaves code to the prologue.
        let parameters: Option<syn::Stmt> = (!state_free.is_empty()).then(|| {
            let pats = state_free.iter().map(|(p, ..)| &p.pat);
            let types = state_free.iter().map(|(p, ..)| &p.ty);
            let values = state_free.iter().map(|(.., arg)| arg);
            syn::parse_quote!(let (#(#pats,)*): (#(#types,)*) = (#(#values,)*);)
        });
        for (param, value, dependent, _) in bound {
            if let Some(name) = &param.name {
                self.bind(name.clone(), Some(value), dependent);
            }
        }
        let value = self.body(&helper.f.block);
        self.inlining.pop();
        let own = std::mem::replace(&mut self.prologue, caller.prologue);
        self.scopes = caller.scopes;
        self.time_in_scope = caller.time_in_scope;
        if !own.is_empty() {
            let mut own = own;
            if let Some(parameters) = parameters {
                own.insert(0, Prologue::Stmt(Box::new(parameters)));
            }
            self.prologue.push(Prologue::Scope(own));
        }
        let value = value?;
        if !fits_output(&value, &helper.output) {
            let output = &helper.f.sig.output;
            return Err(self.refuse(
                quote!(#output),
                format_args!(
                    "a value of `{}` that is not of its return type",
                    helper.f.sig.ident
                ),
            ));
        }
        Ok(value)
    }
}
