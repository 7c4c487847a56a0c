//! The impl block of a fixed-size model: the force (or derivative) and energy functions.

use std::collections::BTreeMap;

use proc_macro2::TokenStream;
use syn::{Block, FnArg, Ident, ImplItem, ImplItemFn, ItemImpl, ReturnType, Type};

use crate::errors::Errors;
use crate::helpers::Helpers;
use crate::model::{Model, Order, Role};
use crate::rewrite::rewrite;
use crate::syntax::{is_f64, is_ref_self};

/// The functions the macro reads; everything else in the impl block passes through untouched.
pub(crate) struct Functions {
    /// `fn acceleration` (second-order) or `fn derivative` (first-order).
    pub(crate) force: Option<Function>,
    /// `fn energy`, when defined.
    pub(crate) energy: Option<Function>,
    /// `fn mass` of a first-order model, when defined: its constant mass matrix, emitted as
    /// written.
    pub(crate) mass: Option<ImplItemFn>,
}

/// One user function, ready to be re-emitted with the state as arguments.
pub(crate) struct Function {
    /// The user's function name (`acceleration`), which stays callable as written.
    pub(crate) name: Ident,
    /// The function as written, for the Jacobian's lowering.
    pub(crate) original: ImplItemFn,
    /// The user's `self` token, reused so the rewritten body resolves `self` to the same binding.
    pub(crate) receiver: syn::Receiver,
    /// The user's time argument (`t: f64`), if declared.
    pub(crate) time: Option<syn::PatType>,
    pub(crate) output: Type,
    /// The body with state reads replaced by [`crate::rewrite::state_local`]s.
    pub(crate) body: Block,
    /// State fields the body reads, with the tokens of the first read (`self.x`).
    pub(crate) reads: BTreeMap<String, TokenStream>,
}

/// The name of the force function a model of `order` must define.
pub(crate) fn force_name(order: Order) -> &'static str {
    match order {
        Order::First => "derivative",
        Order::Second => "acceleration",
    }
}

/// Reads the force and energy functions of `item` for `model`, which may call `helpers`.
pub(crate) fn parse(
    item: &ItemImpl,
    model: &Model<'_>,
    helpers: &Helpers,
    errors: &mut Errors,
) -> Functions {
    let force_name = force_name(model.order);
    let mut functions = Functions {
        force: None,
        energy: None,
        mass: None,
    };
    for member in &item.items {
        let ImplItem::Fn(f) = member else { continue };
        if f.sig.ident == force_name {
            functions.force = read(f, model, helpers, true, errors);
        } else if f.sig.ident == "energy" {
            functions.energy = read(f, model, helpers, false, errors);
        } else if model.order == Order::First && f.sig.ident == "mass" {
            functions.mass = super::algebraic::read_mass(f, model, helpers, errors);
        } else if model.order == Order::First && f.sig.ident == "residual" {
            super::algebraic::refuse_residual(f, errors);
        } else if f.sig.ident == force_name_of_other(model.order) {
            errors.at(
                &f.sig.ident,
                format_args!(
                    "`{}` is for {} models, but `{}` is {}; write `fn {force_name}`",
                    f.sig.ident,
                    if model.order == Order::First {
                        "second-order"
                    } else {
                        "first-order"
                    },
                    model.ident(),
                    describe(model.order),
                ),
            );
        }
    }
    if functions.force.is_none() && errors.is_empty() {
        let signature = match model.order {
            Order::Second => {
                let types: Vec<_> = model
                    .with_role(Role::Velocity)
                    .map(|v| model.describe(v.shape))
                    .collect();
                match types.as_slice() {
                    [one] => format!("fn acceleration(&self) -> {one}"),
                    many => format!("fn acceleration(&self) -> ({})", many.join(", ")),
                }
            }
            Order::First => format!("fn derivative(&self) -> {}", model.state_ident()),
        };
        errors.at(
            &item.self_ty,
            format_args!(
                "missing `{signature}` in `impl {}`, which is {}; an optional second argument \
                 `t: f64` receives the time",
                model.ident(),
                describe(model.order)
            ),
        );
    }
    functions
}

fn force_name_of_other(order: Order) -> &'static str {
    match order {
        Order::First => force_name(Order::Second),
        Order::Second => force_name(Order::First),
    }
}

fn describe(order: Order) -> &'static str {
    match order {
        Order::First => "first-order (`#[state]` fields)",
        Order::Second => "second-order (`#[position]`/`#[velocity]` fields)",
    }
}

/// Checks a function's signature and rewrites its body.
fn read(
    f: &ImplItemFn,
    model: &Model<'_>,
    helpers: &Helpers,
    is_force: bool,
    errors: &mut Errors,
) -> Option<Function> {
    let sig = &f.sig;
    let name = &sig.ident;
    let before = errors.len();
    if !sig.generics.params.is_empty() || sig.generics.where_clause.is_some() {
        errors.at(&sig.generics, format_args!("`{name}` cannot be generic"));
    }
    if let Some(token) = sig
        .asyncness
        .as_ref()
        .map(|a| a.span)
        .or(sig.constness.map(|c| c.span))
    {
        errors.at_span(token, format_args!("`{name}` must be a plain `fn`"));
    }
    let mut inputs = sig.inputs.iter();
    let receiver = match inputs.next() {
        Some(FnArg::Receiver(r)) if is_ref_self(r) => Some(r.clone()),
        Some(other) => {
            errors.at(other, format_args!("`{name}` must take `&self`"));
            None
        }
        None => {
            errors.at(name, format_args!("`{name}` must take `&self`"));
            None
        }
    };
    let time = match inputs.next() {
        None => None,
        Some(FnArg::Typed(t)) if is_f64(&t.ty) && is_force => Some(t.clone()),
        Some(other) => {
            let allowed = if is_force {
                "only `&self` and an optional `t: f64`"
            } else {
                "only `&self`"
            };
            errors.at(other, format_args!("`{name}` takes {allowed}"));
            None
        }
    };
    if let Some(extra) = inputs.next() {
        errors.at(
            extra,
            format_args!("`{name}` takes at most `&self` and `t: f64`"),
        );
    }
    let output = match &sig.output {
        ReturnType::Type(_, ty) => Some((**ty).clone()),
        ReturnType::Default => {
            errors.at(name, format_args!("`{name}` must return a value"));
            None
        }
    };
    let (body, reads) = rewrite(&f.block, model, helpers, name, true, errors);
    if errors.len() > before {
        return None;
    }
    Some(Function {
        name: name.clone(),
        original: f.clone(),
        receiver: receiver?,
        time,
        output: output?,
        body,
        reads,
    })
}

/// The velocity fields `force` reads, with the tokens of the first read of each.
pub(crate) fn velocity_reads<'f>(
    force: &'f Function,
    model: &Model<'_>,
) -> Vec<(&'f str, &'f TokenStream)> {
    force
        .reads
        .iter()
        .filter(|(name, _)| {
            model
                .with_role(Role::Velocity)
                .any(|v| v.ident == name.as_str())
        })
        .map(|(name, tokens)| (name.as_str(), tokens))
        .collect()
}
