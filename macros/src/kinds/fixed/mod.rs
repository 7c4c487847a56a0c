//! The fixed-size model front-end: `#[state]` fields (first-order) or `#[position]`/`#[velocity]`
//! fields (second-order) of type `f64`, `[f64; N]` or `SVector<f64, N>`, and one force
//! (`acceleration`) or derivative (`derivative`) function over the whole state.
//!
//! The struct gives the state fields ([`fields`]); the impl block gives the functions
//! ([`functions`]); the force body is lowered by the shared [`crate::lower::lower`] with the
//! state's components as the variables; [`jacobian`] emits its exact Jacobian (by
//! [`tangent`]'s coloured forward mode for big models) and [`generate`] the state type and the
//! runtime trait impls.

mod algebraic;
mod dual;
mod fields;
mod functions;
mod generate;
mod jacobian;
mod layout;
mod parameters;
mod tangent;

pub(crate) use parameters::param_attribute;

use proc_macro2::TokenStream;
use quote::quote;
use syn::{ItemImpl, ItemStruct};

use crate::args::Args;
use crate::errors::Errors;
use crate::kinds::{FrontEnd, Impl, Struct};
use crate::model::{Model, Order};
use crate::validate::{self, FirstOrder, VelocityRead};
use crate::{helpers, lower};

/// Whether the impl block of const-generic `model` is generic over the struct's parameters, in
/// order (`impl<const N: usize> Chain<N>`), as the generated impls must be; reports it if not.
fn generic_impl(model: &crate::model::Model<'_>, imp: &ItemImpl, errors: &mut Errors) -> bool {
    let declared: Vec<_> = imp.generics.const_params().map(|c| &c.ident).collect();
    let arguments: Option<Vec<_>> = match &*imp.self_ty {
        syn::Type::Path(p) => p
            .path
            .segments
            .last()
            .and_then(|last| match &last.arguments {
                syn::PathArguments::AngleBracketed(a) => a
                    .args
                    .iter()
                    .map(|arg| match arg {
                        syn::GenericArgument::Type(syn::Type::Path(t)) => t.path.get_ident(),
                        syn::GenericArgument::Const(syn::Expr::Path(e)) => e.path.get_ident(),
                        _ => None,
                    })
                    .collect(),
                _ => None,
            }),
        _ => None,
    };
    let matches = declared == model.params
        && imp.generics.params.len() == declared.len()
        && arguments.as_ref() == Some(&model.params);
    if !matches {
        let params: Vec<_> = model.params.iter().map(ToString::to_string).collect();
        let names = params.join(", ");
        let consts: Vec<_> = params.iter().map(|p| format!("const {p}: usize")).collect();
        errors.at(
            &imp.self_ty,
            format_args!(
                "write this impl block as `impl<{}> {}<{names}>`: `#[system]` implements the \
                 runtime's traits for every `{}`",
                consts.join(", "),
                model.ident(),
                params.first().map_or("", String::as_str),
            ),
        );
    }
    matches
}

/// The fixed-size front-end: any struct no other kind recognises.
pub(crate) struct Kind;

impl FrontEnd for Kind {
    fn recognises(&self, _: &ItemStruct) -> bool {
        true
    }

    fn method_attributes(&self) -> &'static [&'static str] {
        &[]
    }

    fn takes_parameters(&self) -> bool {
        true
    }

    fn takes_finite_differences(&self) -> bool {
        true
    }

    fn takes_const_parameters(&self) -> bool {
        true
    }

    /// The struct half: the state type, and what the model asks of an integrator, when accepted.
    fn expand_struct(&self, args: &Args, item: &ItemStruct, errors: &mut Errors) -> Option<Struct> {
        // The `#[param]` fields' errors; the parameters themselves are the impl half's.
        let before = errors.len();
        parameters::parse(item, errors);
        let refused_parameters = errors.len() > before;
        let model = fields::parse(item, errors)?;
        algebraic::args_accepted(item, args, errors);
        if refused_parameters {
            return None;
        }
        if model.is_generic() && args.jacobian.dual().is_none() {
            let params = item.fields.iter().filter_map(|f| param_attribute(&f.attrs));
            for attr in params {
                errors.at(
                    attr,
                    "a const-generic model's Jacobian is taken by differences, so `#[system]` \
                     does not generate ∂f/∂p for `#[param]`; add `jacobian = dual` to \
                     `#[system]` for both by dual numbers, or write the array lengths as integer \
                     literals for generated derivatives",
                );
            }
        }
        let first_order = (model.order == Order::First).then(|| FirstOrder {
            second_order: "`#[position]`/`#[velocity]` fields",
            model: format!("`{}` is first-order (`#[state]` fields)", item.ident),
            instead: "`ExplicitEuler` or `Rk4`",
        });
        Some(Struct {
            state: generate::state(&model),
            first_order,
        })
    }

    /// The impl half: the functions → the force's graph → its Jacobian → the runtime trait impls.
    fn expand_impl(
        &self,
        args: &Args,
        item: &ItemStruct,
        imp: &ItemImpl,
        errors: &mut Errors,
    ) -> Impl {
        let rejected = Impl::Rejected {
            silenced: None,
            stand_ins: TokenStream::new(),
        };
        let Some(model) = fields::parse(item, errors) else {
            return rejected;
        };
        if model.is_generic() && !generic_impl(&model, imp, errors) {
            return rejected;
        }
        let before = errors.len();
        let helpers = helpers::parse(imp, &model, errors);
        let helpers_ok = errors.len() == before;
        let functions = functions::parse(imp, &model, &helpers, errors);
        let velocity_read = functions.force.as_ref().and_then(|force| {
            let reads = functions::velocity_reads(force, &model);
            let &(field, tokens) = reads.first()?;
            Some(VelocityRead {
                reader: format!("`acceleration` reads `self.{field}`"),
                at: Some((tokens.clone(), format!("`self.{field}` is read here"))),
            })
        });
        validate::forces(args, velocity_read, errors);
        let generated_jacobian = args.jacobian.off().is_none()
            && args.jacobian.differences().is_none()
            && args.jacobian.dual().is_none()
            && !model.is_generic();
        let lowered = match &functions.force {
            // A helper with a problem has been reported; its calls are not followed.
            Some(force) if generated_jacobian && helpers_ok => {
                match lower::lower(&model, &helpers, &force.original) {
                    Ok(lowered) => Some(lowered),
                    Err(error) => {
                        errors.push(error);
                        None
                    }
                }
            }
            _ => None,
        };
        let params = parameters::parse(item, errors);
        if let (Some(first), Some(no_jacobian)) = (params.first(), args.jacobian.off()) {
            errors.at(
                no_jacobian,
                format_args!(
                    "`jacobian = false` turns off the generated derivatives, ∂f/∂p of \
                     `#[param]` `{first}` among them"
                ),
            );
        }
        if let (Some(first), Some(differences)) = (params.first(), args.jacobian.differences()) {
            errors.at(
                differences,
                format_args!(
                    "`jacobian = finite_differences` turns off the generated derivatives, ∂f/∂p \
                     of `#[param]` `{first}` among them (sensitivities need them exact; \
                     `jacobian = dual` keeps them)"
                ),
            );
        }
        // ∂f/∂p from a copy of the one lowered force (the Jacobian differentiates the other).
        let parameters = match (&lowered, &functions.force) {
            (Some(lowered), Some(force)) if !params.is_empty() => {
                parameters::parameters(&model, &params, lowered.clone(), force, imp, errors)
            }
            _ => TokenStream::new(),
        };
        if !errors.is_empty() {
            return Impl::Rejected {
                silenced: None,
                stand_ins: stand_ins(&model, args, params.len(), imp),
            };
        }
        // A const-generic model's code is not lowered (its loops run to `N`): differences.
        let differences = args.jacobian.differences().is_some()
            || (model.is_generic()
                && args.jacobian.off().is_none()
                && args.jacobian.dual().is_none());
        let generated = generate::model_impls(
            &model,
            args,
            &functions,
            imp,
            lowered.is_some() || differences || args.jacobian.dual().is_some(),
        );
        let jacobian = match (lowered, &functions.force) {
            (Some(lowered), Some(force)) => jacobian::jacobian(&model, lowered, force, imp),
            (None, Some(force)) if args.jacobian.dual().is_some() => {
                dual::jacobian(&model, force, &helpers, &params, imp)
            }
            (None, Some(force)) if differences => jacobian::differences(&model, force, imp),
            _ => TokenStream::new(),
        };
        Impl::Accepted(quote!(#generated #jacobian #parameters))
    }
}

/// For a model whose impl block was rejected: the `Jacobian` (unless `jacobian = false`) and
/// `Parameters` (with `#[param]`s) it would have had, their bodies never run, so that code
/// calling `model.jacobian_matrix(..)` or `odyn::fit` on it draws no follow-on error.
fn stand_ins(model: &Model<'_>, args: &Args, parameters: usize, imp: &ItemImpl) -> TokenStream {
    let self_ty = &imp.self_ty;
    let (impl_generics, _, where_clause) = imp.generics.split_for_impl();
    let state = model.state_type();
    let never = quote!(::core::unreachable!(
        "odyn rejected this model at compile time"
    ));
    let jacobian = if args.jacobian.off().is_none() {
        let matrix = if !model.is_generic() && model.len() <= layout::SMALL {
            let n = model.len_tokens();
            quote!(::odyn::__private::nalgebra::SMatrix<f64, #n, #n>)
        } else {
            quote!(::odyn::FaerDense)
        };
        quote! {
            #[automatically_derived]
            impl #impl_generics ::odyn::Jacobian for #self_ty #where_clause {
                type Matrix = #matrix;
                const NONZEROS: &'static [(usize, usize)] = &[];
                fn jacobian_matrix(&self, _: &#state) -> #matrix {
                    #never
                }
                fn jacobian(&self, _: f64, _: &#state, _: &mut #matrix) {
                    #never
                }
            }
        }
    } else {
        TokenStream::new()
    };
    let parameters = if parameters > 0 {
        quote! {
            #[automatically_derived]
            impl #impl_generics ::odyn::Parameters for #self_ty #where_clause {
                type Values = [f64; #parameters];
                const NAMES: &'static [&'static str] = &[];
                fn parameter_values(&self) -> [f64; #parameters] {
                    #never
                }
                fn set_parameter_values(&mut self, _: [f64; #parameters]) {
                    #never
                }
                fn parameters(&self) -> ::std::vec::Vec<f64> {
                    #never
                }
                fn write_parameters(&mut self, _: &[f64]) {
                    #never
                }
                fn parameter_jacobian(
                    &self,
                    _: f64,
                    _: &#state,
                    _: &mut ::odyn::__private::nalgebra::DMatrix<f64>,
                ) {
                    #never
                }
            }
        }
    } else {
        TokenStream::new()
    };
    quote!(#jacobian #parameters)
}
