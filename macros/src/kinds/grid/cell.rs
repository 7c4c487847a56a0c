//! The impl block of a field model: its one `#[cell]` kernel, found and checked — its stencil,
//! place and time arguments, and the rates it returns.

use syn::{FnArg, Ident, ImplItem, ImplItemFn, ItemImpl, Pat, ReturnType, Type};

use super::Fields;
use crate::errors::Errors;
use crate::syntax::{
    attribute, has_attribute, int_literal, is_f64, is_ref_self, names_type, no_arguments,
};

/// The `#[cell]` kernel.
pub(crate) struct Cell {
    pub(crate) f: ImplItemFn,
    /// Its stencil arguments, each the index of the field it is named after.
    pub(crate) stencils: Vec<(Ident, usize)>,
    /// Every argument after `&self`, in order.
    pub(crate) arguments: Vec<Argument>,
    /// Its time argument, if it takes one.
    pub(crate) time: Option<Ident>,
    /// Whether it returns `f64` (one field) rather than `[f64; F]`.
    pub(crate) scalar: bool,
}

/// An argument of the `#[cell]` kernel.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Argument {
    /// The stencil of field k.
    Stencil(usize),
    /// The stencil of coefficient grid k (a parameter).
    Coefficient(usize),
    /// The cell's position along x, along y; the time.
    X,
    Y,
    T,
}

impl Argument {
    /// The argument taking the place value `name` (`x`, `y`, `t`), if it is one.
    fn place(name: &str) -> Option<Self> {
        match name {
            "x" => Some(Argument::X),
            "y" => Some(Argument::Y),
            "t" => Some(Argument::T),
            _ => None,
        }
    }
}

/// Finds and checks the one `#[cell]` method.
pub(super) fn parse_cell(imp: &ItemImpl, fields: &Fields<'_>, errors: &mut Errors) -> Option<Cell> {
    let model = &fields.item.ident;
    let mut found: Option<&ImplItemFn> = None;
    for member in &imp.items {
        let ImplItem::Fn(f) = member else { continue };
        let name = &f.sig.ident;
        if has_attribute(&f.attrs, "cell") {
            if found.is_some() {
                errors.at(
                    name,
                    "a field model has one `#[cell]` method, returning every field's rate",
                );
            }
            found = Some(f);
        } else if ["acceleration", "derivative", "energy", "potential"]
            .contains(&name.to_string().as_str())
        {
            errors.at(
                name,
                format_args!(
                    "`{name}` is not read in field model `{model}`; its right-hand side is one \
                     `#[cell]` method: `fn rate(&self, u: Stencil) -> f64`"
                ),
            );
        }
    }
    let Some(f) = found else {
        errors.at(
            &imp.self_ty,
            format_args!(
                "field model `{model}` has no `#[cell]` method; write the rate of every field at \
                 one cell from stencils named like the fields: \
                 `#[cell] fn rate(&self, u: Stencil) -> f64`"
            ),
        );
        return None;
    };
    let before = errors.len();
    if let Some(attr) = attribute(&f.attrs, &["cell"]) {
        no_arguments(attr, "`#[cell]` takes no arguments", errors);
    }
    let name = &f.sig.ident;
    if !f.sig.generics.params.is_empty() {
        errors.at(&f.sig.generics, format_args!("`{name}` cannot be generic"));
    }
    let mut inputs = f.sig.inputs.iter();
    match inputs.next() {
        Some(FnArg::Receiver(r)) if is_ref_self(r) => {}
        _ => errors.at(&f.sig, format_args!("`{name}` must take `&self` first")),
    }
    let mut stencils: Vec<(Ident, usize)> = Vec::new();
    let mut arguments = Vec::new();
    let mut time = None;
    for input in inputs {
        let FnArg::Typed(t) = input else { continue };
        let Pat::Ident(p) = &*t.pat else {
            errors.at(&t.pat, "a stencil argument is a plain name, the field's");
            continue;
        };
        if is_f64(&t.ty) {
            match Argument::place(&p.ident.to_string()) {
                Some(place) if arguments.contains(&place) => {
                    errors.at(&p.ident, format_args!("`{}` is taken twice", p.ident))
                }
                Some(place) => {
                    if place == Argument::T {
                        time = Some(p.ident.clone());
                    }
                    arguments.push(place);
                }
                None => errors.at(
                    &p.ident,
                    format_args!(
                        "`{name}` takes a number only as the cell's position or the time, named \
                         `x`, `y` or `t`; a field's values come through a `Stencil` named like \
                         the field"
                    ),
                ),
            }
            continue;
        }
        if !names_type(&t.ty, "Stencil") {
            errors.at(
                &t.ty,
                format_args!(
                    "`{name}` takes one `odyn::grid::Stencil` per field it reads, named like the \
                     field, and may take the cell's position and the time as `x: f64`, \
                     `y: f64`, `t: f64`"
                ),
            );
            continue;
        }
        if let Some(k) = fields.coefficients.iter().position(|c| **c == p.ident) {
            if arguments.contains(&Argument::Coefficient(k)) {
                errors.at(
                    &p.ident,
                    format_args!("the stencil of `{}` is taken twice", p.ident),
                );
            }
            arguments.push(Argument::Coefficient(k));
            continue;
        }
        match fields.fields.iter().position(|f| **f == p.ident) {
            Some(_) if stencils.iter().any(|(s, _)| *s == p.ident) => errors.at(
                &p.ident,
                format_args!("the stencil of `{}` is taken twice", p.ident),
            ),
            Some(index) => {
                stencils.push((p.ident.clone(), index));
                arguments.push(Argument::Stencil(index));
            }
            None => {
                let listed = |names: &[&Ident]| {
                    names
                        .iter()
                        .map(|f| format!("`{f}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                };
                let coefficients = if fields.coefficients.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", listed(&fields.coefficients))
                };
                errors.at(
                    &p.ident,
                    format_args!(
                        "`{model}` has no `#[field]` called `{}`; a stencil argument is named \
                         like the field it reads ({}), or like a coefficient `Grid` of the \
                         model{coefficients}",
                        p.ident,
                        listed(&fields.fields)
                    ),
                )
            }
        }
    }
    let count = fields.fields.len();
    let scalar = match &f.sig.output {
        ReturnType::Type(_, ty) if count == 1 && is_f64(ty) => true,
        ReturnType::Type(_, ty) if is_array_of(ty, count) => false,
        _ => {
            let wanted = if count == 1 {
                "`f64`".to_string()
            } else {
                format!("`[f64; {count}]`")
            };
            errors.at(
                &f.sig,
                format_args!(
                    "`{name}` must return the rate of each of the {count} field{s} at the cell, \
                     in declaration order: {wanted}",
                    s = if count == 1 { "" } else { "s" }
                ),
            );
            false
        }
    };
    (errors.len() == before).then(|| Cell {
        f: f.clone(),
        stencils,
        arguments,
        time,
        scalar,
    })
}

/// `ty` is `[f64; n]`.
fn is_array_of(ty: &Type, n: usize) -> bool {
    matches!(ty, Type::Array(a)
        if is_f64(&a.elem) && int_literal(&a.len) == Some(n))
}
