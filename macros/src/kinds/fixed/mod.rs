//! The fixed-size model front-end: `#[state]` fields (first-order) or `#[position]`/`#[velocity]`
//! fields (second-order) of type `f64`, `[f64; N]` or `SVector<f64, N>`, and one force
//! (`acceleration`) or derivative (`derivative`) function over the whole state.
//!
//! The struct gives the state fields ([`fields`]); the impl block gives the functions
//! ([`functions`]); the force body is lowered by the shared [`crate::lower::lower`] with the
//! state's components as the variables; [`jacobian`] emits its exact Jacobian (by
//! [`tangent`]'s coloured forward mode for big models) and [`generate`] the state type and the
//! runtime trait impls.

mod fields;
mod functions;
mod generate;
mod jacobian;
mod layout;
mod tangent;

use proc_macro2::TokenStream;
use quote::quote;
use syn::{ItemImpl, ItemStruct};

use crate::args::Args;
use crate::errors::{Errors, with_error};
use crate::lower;
use crate::model::Order;

/// The struct half: the struct without odyn's attributes, and its state type when accepted.
pub(crate) fn expand_struct(
    item: &ItemStruct,
    args: &Args,
    errors: &mut Errors,
) -> (ItemStruct, Option<TokenStream>) {
    let model = fields::parse(item, errors);
    if let (Some(model), Some((ident, info))) = (&model, &args.integrator)
        && info.needs_second_order
        && model.order == Order::First
    {
        errors.at(
            ident,
            format_args!(
                "`{ident}` needs a second-order model (`#[position]`/`#[velocity]` fields), but \
                 `{}` is first-order (`#[state]` fields); use `ExplicitEuler` or `Rk4`",
                item.ident
            ),
        );
    }
    (
        crate::syntax::strip_field_attributes(item),
        model.map(|m| generate::state(&m)),
    )
}

/// The impl half: the functions → the force's graph → its Jacobian → the runtime trait impls.
pub(crate) fn expand_impl(args: &Args, item: &ItemStruct, imp: &ItemImpl) -> TokenStream {
    let mut errors = Errors::default();
    let Some(model) = fields::parse(item, &mut errors) else {
        return with_error(
            imp,
            errors.finish().expect_err("a rejected model has errors"),
        );
    };
    let functions = functions::parse(imp, &model, &mut errors);
    if let (Some((ident, info)), Some(force)) = (&args.integrator, &functions.force)
        && info.needs_velocity_free_forces
    {
        let reads = functions::velocity_reads(force, &model);
        if let Some((field, tokens)) = reads.first() {
            errors.at(
                ident,
                format_args!(
                    "`{ident}` needs forces that do not read velocities, but `acceleration` reads \
                     `self.{field}`; use `VelocityVerlet` or `Leapfrog`"
                ),
            );
            errors.at(tokens, format_args!("`self.{field}` is read here"));
        }
    }
    let lowered = match (&functions.force, &args.no_jacobian) {
        (Some(force), None) => match lower::lower(&model, &force.original) {
            Ok(lowered) => Some(lowered),
            Err(error) => {
                errors.push(error);
                None
            }
        },
        _ => None,
    };
    if let (Some(no), Some((ident, info))) = (&args.no_jacobian, &args.integrator)
        && info.needs_jacobian
    {
        errors.at(
            no,
            format_args!("`{ident}` needs the Jacobian that `jacobian = false` turns off"),
        );
    }
    match errors.finish() {
        Ok(()) => {
            let generated = generate::model_impls(&model, args, &functions, imp, lowered.is_some());
            let jacobian = match (lowered, &functions.force) {
                (Some(lowered), Some(force)) => jacobian::jacobian(&model, lowered, force, imp),
                _ => TokenStream::new(),
            };
            quote!(#imp #generated #jacobian)
        }
        Err(error) => {
            let stub = crate::generate::stub_model(model.ident(), &model.state_ident());
            let rejected = with_error(imp, error);
            quote!(#rejected #stub)
        }
    }
}
