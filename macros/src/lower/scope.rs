//! Locals and their values, `let` patterns, and which expressions read the state or the time.

use std::collections::HashMap;

use proc_macro2::TokenStream;
use quote::quote;
use syn::visit::{self, Visit};
use syn::{Expr, Ident, Member, Pat, Stmt};

use super::names::{Targets, any_ident, path_name, pattern_names};
use super::{Lowering, MAX_DEPTH, Prologue, Value};
use crate::syntax::is_self;

/// A local in scope.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Binding {
    /// Its value in the graph; `None` for a local the lowering does not follow (bound by a
    /// `match` pattern, or a `let` pattern of an opaque value): expressions that use it stay the
    /// user's code, evaluated in the prologue, where the local exists.
    pub(super) value: Option<Value>,
    /// Whether it depends on the state.
    pub(super) dependent: bool,
}

impl Lowering<'_> {
    pub(super) fn bind(&mut self, name: String, value: Option<Value>, dependent: bool) {
        let scope = self.scopes.last_mut().expect("there is always a scope");
        scope.insert(name, Binding { value, dependent });
    }

    pub(super) fn lookup(&self, name: &str) -> Option<&Binding> {
        self.scopes.iter().rev().find_map(|scope| scope.get(name))
    }

    /// Replaces the binding of `name` in the innermost scope that has it.
    pub(super) fn rebind(&mut self, name: &str, binding: Binding) {
        for scope in self.scopes.iter_mut().rev() {
            if let Some(slot) = scope.get_mut(name) {
                *slot = binding;
                return;
            }
        }
    }

    /// Binds the names of `pat` to the parts of `value`: a plain name, `_`, a tuple pattern of a
    /// tuple (or of a vector's components), a slice pattern of a vector, with type ascriptions.
    /// Returns false when the pattern does not fit the value's shape.
    pub(super) fn bind_pattern(&mut self, pat: &Pat, value: Value, dependent: bool) -> bool {
        match pat {
            Pat::Ident(p) if p.subpat.is_none() => {
                self.bind(p.ident.to_string(), Some(value), dependent);
                true
            }
            Pat::Wild(_) => true,
            Pat::Type(t) => self.bind_pattern(&t.pat, value, dependent),
            Pat::Paren(p) => self.bind_pattern(&p.pat, value, dependent),
            Pat::Tuple(t) => {
                let parts = match value {
                    Value::Tuple(parts) => parts,
                    Value::Vector(v) => v.into_iter().map(Value::Scalar).collect(),
                    Value::Scalar(_) | Value::Rows(_) => return false,
                };
                parts.len() == t.elems.len()
                    && t.elems
                        .iter()
                        .zip(parts)
                        .all(|(p, v)| self.bind_pattern(p, v, dependent))
            }
            Pat::Slice(s) => match value {
                Value::Vector(v) if v.len() == s.elems.len() => s
                    .elems
                    .iter()
                    .zip(v)
                    .all(|(p, x)| self.bind_pattern(p, Value::Scalar(x), dependent)),
                Value::Rows(r) if r.len() == s.elems.len() => s
                    .elems
                    .iter()
                    .zip(r)
                    .all(|(p, row)| self.bind_pattern(p, Value::Vector(row), dependent)),
                _ => false,
            },
            _ => false,
        }
    }

    /// A value of `shape`'s shape whose parts read the local `name` back by name (`m`, `v[0]`,
    /// `pair.1`): opaque values the prologue computes after the code that changed the local.
    pub(super) fn read_back(&mut self, name: TokenStream, shape: &Value) -> Value {
        match shape {
            Value::Scalar(_) => Value::Scalar(self.opaque(name)),
            Value::Vector(v) => Value::Vector(
                (0..v.len())
                    .map(|i| self.opaque(quote!(#name[#i])))
                    .collect(),
            ),
            Value::Tuple(parts) => Value::Tuple(
                parts
                    .iter()
                    .enumerate()
                    .map(|(i, part)| {
                        let index = syn::Index::from(i);
                        self.read_back(quote!(#name.#index), part)
                    })
                    .collect(),
            ),
            Value::Rows(rows) => Value::Rows(
                rows.iter()
                    .enumerate()
                    .map(|(i, row)| {
                        (0..row.len())
                            .map(|j| self.opaque(quote!(#name[#i][#j])))
                            .collect()
                    })
                    .collect(),
            ),
        }
    }

    /// Binds every name `pat` introduces as a local the lowering does not follow.
    pub(super) fn bind_unfollowed(&mut self, pat: &Pat) {
        for name in pattern_names(pat) {
            self.bind(name, None, false);
        }
    }

    /// Whether `e` reads the state: `self.<state field>`, or a local bound to a state-dependent
    /// value. Conservatively true for expressions nested deeper than [`MAX_DEPTH`].
    pub(super) fn depends(&self, e: &Expr) -> bool {
        let mut finder = Reads {
            lowering: self,
            time: false,
            found: false,
            depth: 0,
        };
        finder.visit_expr(e);
        finder.found
    }

    /// Whether `e` mentions the time argument.
    pub(super) fn reads_time(&self, e: &Expr) -> bool {
        let mut finder = Reads {
            lowering: self,
            time: true,
            found: false,
            depth: 0,
        };
        finder.visit_expr(e);
        finder.found
    }

    pub(super) fn depends_tokens(&self, tokens: &TokenStream) -> bool {
        any_ident(tokens, &|i| {
            self.lookup(&i.to_string()).is_some_and(|b| b.dependent)
        })
    }

    /// Whether `tokens` name a local in scope.
    pub(super) fn reads_locals(&self, tokens: &TokenStream) -> bool {
        any_ident(tokens, &|i| self.lookup(&i.to_string()).is_some())
    }

    pub(super) fn is_time(&self, name: &str) -> bool {
        self.time_in_scope
            && self.time.as_ref().is_some_and(|(t, _)| t == name)
            && self.lookup(name).is_none()
    }

    /// Whether `name` is the time, or a local whose value was computed from it (`let s = t;`):
    /// either way, code odyn cannot see into that reads it makes ∂f/∂t inexact.
    fn reads_time_name(&self, name: &str) -> bool {
        if self.is_time(name) {
            return true;
        }
        let (
            Some((_, time)),
            Some(Binding {
                value: Some(value), ..
            }),
        ) = (&self.time, self.lookup(name))
        else {
            return false;
        };
        let mut ids = Vec::new();
        flatten(value, &mut ids);
        self.graph
            .reachable(ids)
            .into_iter()
            .any(|id| matches!(self.graph.node(id), crate::ir::Node::Var(k) if k == *time))
    }
}

/// The graph nodes of a value.
fn flatten(value: &Value, out: &mut Vec<crate::ir::ExprId>) {
    match value {
        Value::Scalar(id) => out.push(*id),
        Value::Vector(ids) => out.extend_from_slice(ids),
        Value::Tuple(parts) => parts.iter().for_each(|part| flatten(part, out)),
        Value::Rows(rows) => rows.iter().for_each(|row| out.extend_from_slice(row)),
    }
}

/// Finds reads of the state (or, with `time`, of the time).
struct Reads<'l, 'm> {
    lowering: &'l Lowering<'m>,
    time: bool,
    found: bool,
    depth: u32,
}

impl<'ast> Visit<'ast> for Reads<'_, '_> {
    fn visit_expr(&mut self, e: &'ast Expr) {
        if self.found {
            return;
        }
        if self.depth > MAX_DEPTH {
            // Too deep to follow: count it as read, so the lowering refuses it at its depth.
            self.found = true;
            return;
        }
        match e {
            Expr::Field(f) if is_self(&f.base) => {
                if let Member::Named(name) = &f.member {
                    self.found |= !self.time && self.lowering.model.field(name).is_some();
                }
            }
            Expr::Path(_) => {
                if let Some(name) = path_name(e) {
                    self.found |= if self.time {
                        self.lowering.reads_time_name(&name)
                    } else {
                        self.lowering.lookup(&name).is_some_and(|b| b.dependent)
                    };
                }
            }
            _ => {
                self.depth += 1;
                visit::visit_expr(self, e);
                self.depth -= 1;
            }
        }
    }

    fn visit_macro(&mut self, m: &'ast syn::Macro) {
        if self.time {
            self.found |= m.tokens.clone().into_iter().any(|t| match t {
                proc_macro2::TokenTree::Ident(i) => self.lowering.reads_time_name(&i.to_string()),
                _ => false,
            });
        } else {
            self.found |= self.lowering.depends_tokens(&m.tokens);
        }
    }
}

/// The locals a statement may assign: targets of `=` and `op=`, receivers of method calls (which
/// may take `&mut self`), and `&mut` borrows — each a bound local, as the user spelled it (its
/// span resolves to the user's local in generated code).
pub(super) fn assigned(lowering: &Lowering<'_>, e: &Expr) -> Vec<Ident> {
    let mut found = Targets::default();
    found.visit_expr(e);
    let mut names: Vec<Ident> = Vec::new();
    for ident in found.0 {
        if lowering.lookup(&ident.to_string()).is_some() && !names.contains(&ident) {
            names.push(ident);
        }
    }
    names
}

/// The scopes of locals, innermost last.
pub(super) type Scopes = Vec<HashMap<String, Binding>>;

/// The first statement of `prologue` (its branches' arms included) that assigns, borrows
/// mutably or calls a method on a local bound in `outer`, and that local's name.
pub(super) fn changes_outer<'p>(
    prologue: &'p [Prologue],
    outer: &Scopes,
) -> Option<(&'p Stmt, String)> {
    for item in prologue {
        match item {
            Prologue::Stmt(stmt) => {
                let mut targets = Targets::default();
                syn::visit::Visit::visit_stmt(&mut targets, stmt);
                if let Some(name) = targets
                    .0
                    .iter()
                    .map(ToString::to_string)
                    .find(|name| outer.iter().any(|scope| scope.contains_key(name)))
                {
                    return Some((stmt, name));
                }
            }
            Prologue::Branch(branch) => {
                if let Some(found) = branch.arms.iter().find_map(|arm| changes_outer(arm, outer)) {
                    return Some(found);
                }
            }
            // A helper's code changes only its own locals.
            Prologue::Opaque(..) | Prologue::Scope(_) => {}
        }
    }
    None
}
