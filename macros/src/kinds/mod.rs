//! Model kinds, one front-end each. A front-end recognises its struct and impl block, reports
//! what it rejects at the offending tokens, and hands the shared stages what they need: the
//! state description ([`crate::model::Model`]) and each body to lower
//! ([`crate::lower::lower`] for a whole-state function, [`crate::lower::lower_kernel`] for a
//! kernel of its arguments). Lowering, differentiation ([`crate::derivative`],
//! [`crate::sparsity`]) and straight-line code ([`crate::generate`]) know nothing of the kinds;
//! each kind's own `generate` emits the runtime trait impls that call into its runtime module.
//!
//! - [`fixed`]: `#[state]` or `#[position]`/`#[velocity]` fields of fixed size (`odyn::Model`);
//! - [`particles`]: `Vec<VectorD<f64>>` positions and velocities with `#[pair]`/`#[particle]`
//!   kernels (`odyn::particles`);
//! - [`grid`]: `#[field]` grids with one `#[cell]` stencil kernel (`odyn::grid`).
//!
//! This file is the one path every kind's expansion takes: the attribute checks
//! ([`attributes`]), the front-end's reading, the checks against the integrator
//! ([`crate::validate`]), and the accepted or rejected output. Adding a kind is a directory here
//! with a type implementing [`FrontEnd`], its row in [`KINDS`], and its runtime module.

mod attributes;
pub(crate) mod fixed;
pub(crate) mod grid;
pub(crate) mod particles;

use proc_macro2::TokenStream;
use quote::{ToTokens, quote};
use syn::{ItemImpl, ItemStruct};

use crate::args::{self, Args};
use crate::errors::Errors;
use crate::generate::{self, Forward};
use crate::model::state_ident;
use crate::syntax::{strip_field_attributes, strip_method_attributes};
use crate::validate::{self, FirstOrder};

/// A model kind's front-end: it recognises its structs, reads struct and impl block, reports
/// what it rejects to the [`Errors`] it is given, and generates the kind's runtime trait impls.
pub(crate) trait FrontEnd: Sync {
    /// Whether `item` is a model of this kind (asked in the order of [`KINDS`]).
    fn recognises(&self, item: &ItemStruct) -> bool;

    /// odyn's attributes on this kind's methods (its kernels'), if any: stripped from the impl
    /// block, and their near misses reported.
    fn method_attributes(&self) -> &'static [&'static str];

    /// The struct half: the state type and what the model asks of an integrator, when accepted.
    fn expand_struct(&self, args: &Args, item: &ItemStruct, errors: &mut Errors) -> Option<Struct>;

    /// Whether the kind generates ∂f/∂p for `#[param]` fields.
    fn takes_parameters(&self) -> bool {
        false
    }

    /// Whether the kind can take its Jacobian from the model's code run as written, by finite
    /// differences (`jacobian = finite_differences`) or over dual numbers (`jacobian = dual`).
    fn takes_finite_differences(&self) -> bool {
        false
    }

    /// Whether the kind's struct may have const parameters (`struct Chain<const N: usize>`) for
    /// the lengths of its state arrays.
    fn takes_const_parameters(&self) -> bool {
        false
    }

    /// The impl half: the items generated after the impl block, or the rejection.
    fn expand_impl(
        &self,
        args: &Args,
        item: &ItemStruct,
        imp: &ItemImpl,
        errors: &mut Errors,
    ) -> Impl;
}

/// The model kinds, one row each: the first that recognises a struct reads it. A `#[mass]`,
/// `#[pinned]` or `Vec` position makes a particle model, a `#[field]` a grid model, anything
/// else a fixed-size model.
const KINDS: [&dyn FrontEnd; 3] = [&particles::Kind, &grid::Kind, &fixed::Kind];

/// odyn's attributes on the methods of any kind's impl block (`cell`, `pair`, `particle`): what
/// is stripped from the impl block of a struct that was rejected before its kind was known.
pub(crate) fn method_attributes() -> Vec<&'static str> {
    KINDS
        .iter()
        .flat_map(|kind| kind.method_attributes().iter().copied())
        .collect()
}

/// The front-end of `item`'s kind.
fn front_end(item: &ItemStruct) -> &'static dyn FrontEnd {
    KINDS
        .into_iter()
        .find(|kind| kind.recognises(item))
        .unwrap_or(&fixed::Kind)
}

/// What a front-end makes of a struct it accepts.
pub(crate) struct Struct {
    /// The state type `<Model>State` and its impls.
    pub(crate) state: TokenStream,
    /// `Some` for a first-order model: how to say so when the integrator needs a second-order one.
    pub(crate) first_order: Option<FirstOrder>,
}

/// What a front-end makes of an impl block.
pub(crate) enum Impl {
    /// The runtime trait impls, emitted after the impl block.
    Accepted(TokenStream),
    /// Rejected, its errors recorded; `silenced` names a method whose body must not be emitted
    /// as written (rustc would report its errors a second time); `stand_ins` are impls of the
    /// traits the model would have had beyond `Model` (its `Jacobian`, its `Parameters`), whose
    /// bodies never run, so calls of their methods draw no follow-on errors.
    Rejected {
        silenced: Option<syn::Ident>,
        stand_ins: TokenStream,
    },
}

/// The struct half of `#[system]`: the struct without odyn's attributes, its state type, and the
/// forwarding macro to the impl block (which passes the impl block through untouched when the
/// struct was rejected).
pub(crate) fn expand_struct(args_tokens: TokenStream, item: &ItemStruct) -> TokenStream {
    let mut errors = Errors::default();
    let args = args::parse(args_tokens.clone(), &mut errors);
    let item = &attributes::unknown_attributes(item, &mut errors);
    let stripped = strip_field_attributes(item);
    let state = if let Some(refusal) = unsupported_shape(item, front_end(item)) {
        // One error: the fields of a generic model (`[f64; N]`, `k: T`) would each be refused
        // only because of the generics, and a tuple struct's have no names to read.
        errors.push(refusal);
        validate::structure(&args, None, &mut errors);
        None
    } else {
        let kind = front_end(item);
        let before = errors.len();
        if !kind.takes_parameters() {
            refuse_parameters(item, &mut errors);
        }
        if let Some(word) = args.jacobian.of_code()
            && !kind.takes_finite_differences()
        {
            errors.at(
                word,
                format_args!(
                    "`jacobian = {word}` is for fixed-size models: particle and field models get \
                     their sparse Jacobian generated from their kernels"
                ),
            );
        }
        let accepted = kind.expand_struct(&args, item, &mut errors);
        // A struct the front-end reported on is rejected whole, however it was returned.
        let accepted = accepted.filter(|_| errors.len() == before);
        let first_order = accepted.as_ref().and_then(|s| s.first_order.as_ref());
        validate::structure(&args, first_order, &mut errors);
        accepted.map(|s| s.state)
    };
    match (errors.finish(), state) {
        (Ok(()), Some(state)) => {
            let forwarder = generate::forwarder(item, &args_tokens, Forward::Accepted);
            let check = generate::impl_check(item);
            quote!(#stripped #state #forwarder #check)
        }
        // Only the arguments, or their fit with the model, were wrong (`rtol = -1.0`): the
        // model still expands, so its uses draw no errors of their own.
        (Err(error), Some(state)) => {
            let error = error.to_compile_error();
            let forwarder = generate::forwarder(item, &args_tokens, Forward::Reported);
            quote!(#stripped #error #state #forwarder)
        }
        (result, None) => {
            let error = result.err().map(|e| e.to_compile_error());
            let forwarder = generate::forwarder(item, &args_tokens, Forward::Rejected);
            let stub = generate::rejected_struct(item);
            quote!(#stripped #error #forwarder #stub)
        }
    }
}

/// Reports each `#[param]` of a model whose kind does not generate ∂f/∂p.
fn refuse_parameters(item: &ItemStruct, errors: &mut Errors) {
    for field in &item.fields {
        if let Some(attr) = fixed::param_attribute(&field.attrs) {
            errors.at(
                attr,
                "`#[param]` (∂f/∂p for sensitivities and fitting) is generated for fixed-size \
                 models only so far, not for particle or grid models",
            );
        }
    }
}

/// The error for a struct `kind` cannot read: one generic over more than array lengths, or one
/// without named fields.
fn unsupported_shape(item: &ItemStruct, kind: &dyn FrontEnd) -> Option<syn::Error> {
    let generics = &item.generics;
    let lengths_only = "a model's generic parameters can only be array lengths, `const N: usize`: \
                        `#[system]` lays the state out in `f64` components and reads \
                        parameters as `f64` fields";
    for param in &generics.params {
        match param {
            syn::GenericParam::Const(c) if crate::syntax::is_plain(&c.ty, "usize") => {
                if !kind.takes_const_parameters() {
                    return Some(syn::Error::new_spanned(
                        param,
                        "const parameters are for fixed-size models: particle and grid models \
                         are sized at run time, by their state",
                    ));
                }
            }
            syn::GenericParam::Const(c) => {
                return Some(syn::Error::new_spanned(
                    &c.ty,
                    "a const parameter of a model is an array length, of type `usize`",
                ));
            }
            other => return Some(syn::Error::new_spanned(other, lengths_only)),
        }
    }
    if let Some(clause) = &generics.where_clause {
        return Some(syn::Error::new_spanned(clause, lengths_only));
    }
    if !matches!(item.fields, syn::Fields::Named(_)) {
        return Some(syn::Error::new(
            item.ident.span(),
            "a model must be a struct with named fields, such as `struct Spring { x: f64, .. }`",
        ));
    }
    None
}

/// The impl half, with the struct: the impl block without odyn's method attributes and the
/// runtime trait impls of the struct's kind; or, rejected, the impl block, the errors, and a
/// stand-in `Model` impl so the rest of the crate draws no follow-on errors.
pub(crate) fn expand_impl(args: &Args, item: &ItemStruct, imp: &ItemImpl) -> TokenStream {
    let impl_is_generic = !imp.generics.params.is_empty()
        || matches!(&*imp.self_ty, syn::Type::Path(p)
            if p.path.segments.iter().any(|s| !s.arguments.is_none()));
    if impl_is_generic && item.generics.params.is_empty() {
        // Generics on the impl of a plain struct: rustc reports them; the impl block stays, its
        // bodies never run, and nothing more is said.
        let known = method_attributes();
        return generate::never_run(strip_method_attributes(imp, &known), |_| true)
            .into_token_stream();
    }
    let kind = front_end(item);
    let known = kind.method_attributes();
    let mut near_misses = Errors::default();
    let imp = &attributes::unknown_method_attributes(known, imp, &mut near_misses);
    let mut errors = Errors::default();
    let outcome = kind.expand_impl(args, item, imp, &mut errors);
    let stripped = strip_method_attributes(imp, known);
    let expanded = match (errors.finish(), outcome) {
        (Ok(()), Impl::Accepted(generated)) => quote!(#stripped #generated),
        (result, outcome) => {
            let error = result.err().unwrap_or_else(|| {
                syn::Error::new_spanned(&imp.self_ty, "`#[system]` rejected this model")
            });
            let (silenced, stand_ins) = match outcome {
                Impl::Rejected {
                    silenced,
                    stand_ins,
                } => (silenced, stand_ins),
                Impl::Accepted(_) => (None, TokenStream::new()),
            };
            let imp = generate::never_run(stripped, |f| Some(&f.sig.ident) == silenced.as_ref());
            let error = error.to_compile_error();
            let state = state_ident(&item.ident);
            let (_, type_generics, _) = item.generics.split_for_impl();
            let stub = generate::stub_model_with(
                &item.ident,
                quote!(#state #type_generics),
                &item.generics,
            );
            quote!(#imp #error #stub #stand_ins)
        }
    };
    // A near miss was read as the attribute meant: the expansion stands beside its error.
    let near_misses = near_misses.finish().err().map(|e| e.to_compile_error());
    quote!(#expanded #near_misses)
}
