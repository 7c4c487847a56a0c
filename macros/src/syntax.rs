//! The names odyn gives meaning to and the small questions every stage asks of syn nodes ("is
//! this `f64`?", "which of odyn's attributes is on this field?"), answered once (in the manner
//! of serde_derive's `symbol.rs`). Pure reads of syntax: no errors are reported here except by
//! [`no_arguments`], which reports to the caller's [`Errors`].

use syn::{
    Attribute, Expr, GenericArgument, ImplItem, ItemImpl, ItemStruct, Lit, PathArguments, Type,
};

use crate::errors::Errors;

/// odyn's attributes on a model's fields: fixed-size (`state`, `position`, `velocity`,
/// `algebraic`), grid (`field`), particles (`mass`, `pinned`, and `position`/`velocity` of `Vec`
/// type). In this order in the messages that list them (`algebraic` last: it came last).
pub(crate) const FIELD_ATTRIBUTES: [&str; 8] = [
    "state",
    "position",
    "velocity",
    "field",
    "mass",
    "pinned",
    "param",
    "algebraic",
];

/// Rust's own attributes that may go on a struct, its fields, or a method.
pub(crate) const RUST_ATTRIBUTES: [&str; 21] = [
    "doc",
    "cfg",
    "cfg_attr",
    "allow",
    "expect",
    "warn",
    "deny",
    "forbid",
    "deprecated",
    "repr",
    "must_use",
    "non_exhaustive",
    "automatically_derived",
    "inline",
    "cold",
    "track_caller",
    "target_feature",
    "no_mangle",
    "export_name",
    "link_section",
    "rustfmt",
];

/// Whether `ty` is plain `f64`.
pub(crate) fn is_f64(ty: &Type) -> bool {
    is_plain(ty, "f64")
}

/// Whether `ty` is the one-word path `name` (`f64`, `usize`).
pub(crate) fn is_plain(ty: &Type, name: &str) -> bool {
    matches!(ty, Type::Path(p) if p.qself.is_none() && p.path.is_ident(name))
}

/// Whether `ty` is a path to a type called `name` without generic arguments, by any route
/// (`Grid`, `odyn::grid::Grid`): for odyn's own types, which users import as they like.
pub(crate) fn names_type(ty: &Type, name: &str) -> bool {
    matches!(ty, Type::Path(p) if p.qself.is_none()
        && p.path.segments.last().is_some_and(|s| s.ident == name && s.arguments.is_none()))
}

/// `T` of `Vec<T>`.
pub(crate) fn vec_element(ty: &Type) -> Option<&Type> {
    let Type::Path(p) = ty else { return None };
    let last = p.path.segments.last()?;
    if last.ident != "Vec" {
        return None;
    }
    let PathArguments::AngleBracketed(args) = &last.arguments else {
        return None;
    };
    match args.args.iter().collect::<Vec<_>>().as_slice() {
        [GenericArgument::Type(t)] => Some(t),
        _ => None,
    }
}

/// The value of an integer literal, looking through parentheses and invisible groups.
pub(crate) fn int_literal(expr: &Expr) -> Option<usize> {
    match expr {
        Expr::Lit(syn::ExprLit {
            lit: Lit::Int(i), ..
        }) => i.base10_parse().ok(),
        Expr::Group(g) => int_literal(&g.expr),
        Expr::Paren(p) => int_literal(&p.expr),
        _ => None,
    }
}

/// Whether `expr` is `self`.
pub(crate) fn is_self(expr: &Expr) -> bool {
    matches!(expr, Expr::Path(p) if p.qself.is_none() && p.path.is_ident("self"))
}

/// Whether `receiver` is `&self` (not `self`, not `&mut self`): what every function odyn reads
/// takes, so it cannot change the model while it is evaluated.
pub(crate) fn is_ref_self(receiver: &syn::Receiver) -> bool {
    receiver.reference.is_some() && receiver.mutability.is_none()
}

/// The first of `attrs` that is one of `names`.
pub(crate) fn attribute<'a>(attrs: &'a [Attribute], names: &[&str]) -> Option<&'a Attribute> {
    attrs
        .iter()
        .find(|a| names.iter().any(|n| a.path().is_ident(n)))
}

/// Whether `attrs` hold `name`.
pub(crate) fn has_attribute(attrs: &[Attribute], name: &str) -> bool {
    attribute(attrs, &[name]).is_some()
}

/// Reports `message` at the arguments of `attr`, if it has any (`#[cell(x)]`, `#[mass = 1]`).
pub(crate) fn no_arguments(attr: &Attribute, message: impl std::fmt::Display, errors: &mut Errors) {
    if let Err(e) = attr.meta.require_path_only() {
        errors.at_span(e.span(), message);
    }
}

/// The struct as the user wrote it, minus odyn's field attributes (which rustc does not know).
pub(crate) fn strip_field_attributes(item: &ItemStruct) -> ItemStruct {
    let mut item = item.clone();
    for field in &mut item.fields {
        field
            .attrs
            .retain(|a| !FIELD_ATTRIBUTES.iter().any(|n| a.path().is_ident(n)));
    }
    item
}

/// Whether `attr` marks a helper function: `#[odyn::function]` (or `#[function]`, like the
/// kernels' `#[cell]`), which `#[system]` reads on the methods of the model's impl block.
pub(crate) fn is_function_attribute(attr: &Attribute) -> bool {
    let path = attr.path();
    let segments: Vec<String> = path.segments.iter().map(|s| s.ident.to_string()).collect();
    path.segments.iter().all(|s| s.arguments.is_none())
        && match segments.as_slice() {
            [f] => f == "function" && path.leading_colon.is_none(),
            [odyn, f] => odyn == "odyn" && f == "function",
            _ => false,
        }
}

/// The impl block minus the method attributes `names` and `#[odyn::function]` (odyn's, which
/// `#[system]` has read: the helper attribute of its own would report a misplaced helper).
pub(crate) fn strip_method_attributes(imp: &ItemImpl, names: &[&str]) -> ItemImpl {
    let mut imp = imp.clone();
    for member in &mut imp.items {
        if let ImplItem::Fn(f) = member {
            let helper = f.attrs.iter().any(is_function_attribute);
            f.attrs.retain(|a| {
                !names.iter().any(|n| a.path().is_ident(n)) && !is_function_attribute(a)
            });
            // A helper runs inside the derivative: its transcendental calls go through
            // `odyn::math` as the force's do (the `deterministic` feature).
            if helper {
                crate::math::route_block(&mut f.block);
            }
        }
    }
    imp
}
