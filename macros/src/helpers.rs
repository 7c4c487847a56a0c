//! The model's helper functions: methods of its `#[system]` impl block marked
//! `#[odyn::function]`, read and checked here and inlined by [`crate::lower`] wherever the force
//! (or a kernel) calls them.
//!
//! Why in the impl block: an attribute macro sees only the item it is written on, so
//! `#[odyn::function]` on a free `fn` could not hand that function's body to the `#[system]`
//! expansion of another item. `#[system]` on the impl block already reads every method in it, so
//! a helper written there, marked, is read with the force: `fn restoring(&self, x: f64) -> f64`
//! (reading parameters as `self.k`) called as `self.restoring(self.x)`, or
//! `fn restoring(x: f64) -> f64` called as `Self::restoring(self.x)`.
//!
//! Lowering a call lowers the helper's body in a scope of its own, its parameters bound to the
//! arguments' values in the graph: the helper is inlined, so its derivative comes from the same
//! rules as the force's own code, exactly. Its state-free code runs in the prologue in a block
//! of its own ([`crate::lower::Prologue::Scope`]). At run time the force calls the helper as the
//! ordinary method it stays.
//!
//! A helper reads the state only through its arguments (the force's code is evaluated at states
//! other than the struct's own, and so is the helper, called from it), takes numbers (`f64`,
//! `[f64; N]`, `VectorN<f64>`, `SVector<f64, N>`, by value or `&`), returns one of those or a
//! tuple of them, and may call other helpers, but not itself, directly or through others.

mod calls;

use quote::ToTokens;
use syn::{Expr, FnArg, Ident, ImplItem, ImplItemFn, ItemImpl, Pat, ReturnType, Type};

use self::calls::{call_of, recursion};
use crate::errors::Errors;
use crate::model::{Model, Shape, shape_of};
use crate::rewrite::rewrite;
use crate::syntax::{is_function_attribute, is_ref_self};

/// One helper function.
pub(crate) struct Helper {
    /// The method as written: its body is lowered at every call on the state.
    pub(crate) f: ImplItemFn,
    /// Whether it takes `&self` (called `self.f(…)`) or nothing (called `Self::f(…)`).
    pub(crate) receiver: bool,
    pub(crate) params: Vec<Param>,
    pub(crate) output: Output,
}

/// A helper's parameter.
pub(crate) struct Param {
    /// The pattern as written (`x`, `mut x`, `_`).
    pub(crate) pat: Pat,
    /// The name it binds, if any.
    pub(crate) name: Option<String>,
    /// The type as written.
    pub(crate) ty: Type,
    pub(crate) shape: Shape,
}

/// A helper's return type.
pub(crate) enum Output {
    One(Shape),
    Tuple(Vec<Shape>),
}

/// The helpers of one impl block.
pub(crate) struct Helpers {
    /// The model's name: `Spring::f(…)` calls a helper as `Self::f(…)` does.
    model: Ident,
    helpers: Vec<Helper>,
}

impl Helpers {
    /// Every helper, in the order written.
    pub(crate) fn iter(&self) -> impl Iterator<Item = &Helper> {
        self.helpers.iter()
    }

    /// The helpers' names.
    pub(crate) fn names(&self) -> impl Iterator<Item = String> + '_ {
        self.helpers.iter().map(|h| h.f.sig.ident.to_string())
    }

    pub(crate) fn get(&self, name: &str) -> Option<&Helper> {
        self.helpers.iter().find(|h| h.f.sig.ident == name)
    }

    /// The helper a call expression calls, with its arguments: `Self::f(a)` or `Model::f(a)` of a
    /// helper without a receiver, `self.f(a)` of one with `&self`.
    pub(crate) fn called<'e>(&self, e: &'e Expr) -> Option<(&Helper, Vec<&'e Expr>)> {
        let (name, receiver, args) = call_of(e, &self.model)?;
        let helper = self.get(&name)?;
        (helper.receiver == receiver).then(|| (helper, args.iter().collect()))
    }
}

impl crate::rewrite::Methods for Helpers {
    fn is_method(&self, name: &Ident) -> bool {
        self.get(&name.to_string()).is_some_and(|h| h.receiver)
    }
}

/// Whether `f` is marked `#[odyn::function]`.
pub(crate) fn is_marked(f: &ImplItemFn) -> bool {
    f.attrs.iter().any(is_function_attribute)
}

/// Reads the helpers of `imp`; `model` names the state fields a helper may not read through
/// `self`. Each problem is reported at its token, every recursive call at the call; the helpers
/// are returned all the same, so that calls of one with a problem draw no second error (a model
/// with errors is not lowered).
pub(crate) fn parse(imp: &ItemImpl, model: &Model<'_>, errors: &mut Errors) -> Helpers {
    let marked: Vec<&ImplItemFn> = imp
        .items
        .iter()
        .filter_map(|item| match item {
            ImplItem::Fn(f) if is_marked(f) => Some(f),
            _ => None,
        })
        .collect();
    let mut helpers = Helpers {
        model: model.ident().clone(),
        helpers: marked
            .iter()
            .map(|f| Helper {
                f: (*f).clone(),
                receiver: matches!(f.sig.inputs.first(), Some(FnArg::Receiver(_))),
                params: Vec::new(),
                output: Output::One(Shape::Scalar),
            })
            .collect(),
    };
    for (i, f) in marked.iter().enumerate() {
        let (params, output) = read(f, model, &helpers, errors);
        helpers.helpers[i].params = params;
        helpers.helpers[i].output = output;
    }
    recursion(&helpers.model, &marked, errors);
    helpers
}

/// Checks one helper's attribute, signature and body; its parameters and return type, as far
/// as they are numbers.
fn read(
    f: &ImplItemFn,
    model: &Model<'_>,
    names: &Helpers,
    errors: &mut Errors,
) -> (Vec<Param>, Output) {
    let sig = &f.sig;
    let name = &sig.ident;
    for attr in f.attrs.iter().filter(|a| is_function_attribute(a)) {
        crate::syntax::no_arguments(attr, "`#[odyn::function]` takes no arguments", errors);
    }
    if ["acceleration", "derivative", "energy", "potential"].contains(&name.to_string().as_str()) {
        errors.at(
            name,
            format_args!(
                "`{name}` is a function odyn reads as it is; `#[odyn::function]` marks the \
                 helpers it calls"
            ),
        );
    }
    if !sig.generics.params.is_empty() || sig.generics.where_clause.is_some() {
        errors.at(
            &sig.generics,
            format_args!("`#[odyn::function]` `{name}` cannot be generic"),
        );
    }
    if let Some(token) = sig
        .asyncness
        .as_ref()
        .map(ToTokens::to_token_stream)
        .or(sig.unsafety.as_ref().map(ToTokens::to_token_stream))
        .or(sig.abi.as_ref().map(ToTokens::to_token_stream))
        .or(sig.variadic.as_ref().map(ToTokens::to_token_stream))
    {
        errors.at(
            token,
            format_args!("`#[odyn::function]` `{name}` must be a plain `fn`"),
        );
    }
    let mut params = Vec::new();
    for (i, input) in sig.inputs.iter().enumerate() {
        match input {
            FnArg::Receiver(r) if i == 0 && is_ref_self(r) && r.colon_token.is_none() => {}
            FnArg::Receiver(r) => errors.at(
                r,
                format_args!(
                    "`#[odyn::function]` `{name}` takes `&self` or no receiver (it reads \
                     parameters, never changes the model)"
                ),
            ),
            FnArg::Typed(t) => {
                let name_of = match &*t.pat {
                    Pat::Ident(p) if p.by_ref.is_none() && p.subpat.is_none() => {
                        Some(Some(p.ident.to_string()))
                    }
                    Pat::Wild(_) => Some(None),
                    _ => None,
                };
                let Some(param_name) = name_of else {
                    errors.at(
                        &t.pat,
                        format_args!(
                            "`#[odyn::function]` `{name}` takes parameters by name (`x: f64`)"
                        ),
                    );
                    continue;
                };
                match number_shape(&t.ty) {
                    Some(shape) => params.push(Param {
                        pat: (*t.pat).clone(),
                        name: param_name,
                        ty: (*t.ty).clone(),
                        shape,
                    }),
                    None => errors.at(
                        &t.ty,
                        format_args!(
                            "`#[odyn::function]` `{name}` takes numbers: `f64`, `[f64; N]`, \
                             `VectorN<f64>` or `SVector<f64, N>` (by value or `&`), which odyn \
                             differentiates; not `{}`",
                            t.ty.to_token_stream()
                        ),
                    ),
                }
            }
        }
    }
    let output = match &sig.output {
        ReturnType::Default => {
            errors.at(
                name,
                format_args!("`#[odyn::function]` `{name}` must return a value"),
            );
            None
        }
        ReturnType::Type(_, ty) => {
            let output = match &**ty {
                Type::Tuple(t) if !t.elems.is_empty() => t
                    .elems
                    .iter()
                    .map(shape_of)
                    .collect::<Option<Vec<_>>>()
                    .map(Output::Tuple),
                other => shape_of(other).map(Output::One),
            };
            if output.is_none() {
                errors.at(
                    ty,
                    format_args!(
                        "`#[odyn::function]` `{name}` returns numbers: `f64`, `[f64; N]`, \
                         `VectorN<f64>`, `SVector<f64, N>`, or a tuple of them; not `{}`",
                        ty.to_token_stream()
                    ),
                );
            }
            output
        }
    };
    // The body: `self` only to read parameters and to call other helpers, and no state field.
    let (_, reads) = rewrite(&f.block, model, names, name, false, errors);
    if let Some(tokens) = reads.values().next() {
        errors.at(
            tokens,
            format_args!(
                "`#[odyn::function]` `{name}` reads the state only through its arguments, not \
                 through `self`: odyn calls it at states other than the struct's own; pass `{}` \
                 to it as an argument",
                tokens.to_string().replace(' ', "")
            ),
        );
    }
    (params, output.unwrap_or(Output::One(Shape::Scalar)))
}

/// The shape of a helper's parameter type: a number type, or a reference to one.
fn number_shape(ty: &Type) -> Option<Shape> {
    match ty {
        Type::Reference(r) if r.mutability.is_none() && r.lifetime.is_none() => shape_of(&r.elem),
        Type::Paren(p) => number_shape(&p.elem),
        other => shape_of(other),
    }
}

#[cfg(test)]
mod tests;
