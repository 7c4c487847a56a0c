//! Code generation shared by every model kind: the forwarding macro between a struct's expansion
//! and its impl block's, the stub `Model` impl of a rejected model, the `#[system]` arguments as
//! constants, and ([`code`]) the expression graph as straight-line Rust.
//!
//! Generated code names everything by absolute path (`::odyn::…`), binds the state to hygienic
//! locals, and documents every public item so `cargo doc` of a user's crate explains it.

mod code;

use proc_macro2::TokenStream;
use quote::{format_ident, quote, quote_spanned};
use syn::ItemStruct;
use syn::spanned::Spanned;

use crate::args::Args;

pub(crate) use code::{lets, opaques_read, operand, prologue_tokens, straight_line};

/// The name of the `macro_rules!` through which a struct's expansion reaches its impl block's.
///
/// rustc's own error when the impl's call finds no such macro — the struct lacks `#[system]`, or
/// comes after its impl, or lives in another module — cannot be replaced, so the name itself says
/// what is required: "cannot find macro `__odyn_requires_system_on_struct_Spring_above_this_impl`"
/// (a name that stays true in the notes of other errors, where the struct does have it).
pub(crate) fn forwarder_name(model: &syn::Ident) -> syn::Ident {
    format_ident!(
        "__odyn_requires_system_on_struct_{}_above_this_impl",
        model,
        span = model.span()
    )
}

/// A `Model` impl for a model whose impl block was rejected: it is never run (the crate does not
/// compile), but with it the rest of the user's crate type-checks, so the user sees the real error
/// and not "no method named `simulate`" at every call site.
pub(crate) fn stub_model(model: &syn::Ident, state: &syn::Ident) -> TokenStream {
    stub_model_with(model, state, &syn::Generics::default())
}

/// [`stub_model`] for a struct with `generics`.
fn stub_model_with(
    model: &syn::Ident,
    state: &syn::Ident,
    generics: &syn::Generics,
) -> TokenStream {
    let (impl_generics, type_generics, where_clause) = generics.split_for_impl();
    let name = model.to_string();
    let never = quote!(::core::unreachable!(
        "odyn rejected this model at compile time"
    ));
    quote! {
        #[automatically_derived]
        impl #impl_generics ::odyn::Model for #model #type_generics #where_clause {
            type State = #state;
            type SecondOrder = ::odyn::Unavailable<Self>;
            type Jacobian = ::odyn::Unavailable<Self>;
            const NAME: &'static str = #name;
            const DEFAULT_METHOD: ::odyn::Method = ::odyn::Method::Rk4;
            const DEFAULT_DT: ::core::option::Option<f64> = ::core::option::Option::None;
            fn state(&self) -> #state {
                #never
            }
            fn derivative(&self, _: f64, _: &#state, _: &mut #state) {
                #never
            }
            fn energy(&self, _: &#state) -> ::core::option::Option<f64> {
                #never
            }
            fn as_second_order(&self) -> ::core::option::Option<&Self::SecondOrder> {
                ::core::option::Option::None
            }
            fn as_jacobian(&self) -> ::core::option::Option<&Self::Jacobian> {
                ::core::option::Option::None
            }
        }
    }
}

/// For a struct `#[system]` rejected: its state type, as a type without values, and a stub
/// `Model` impl, so that uses of the model elsewhere in the crate (`model.simulate()`, the
/// state's name in signatures) type-check and the user sees the real error alone. Nothing of it
/// runs: the crate does not compile.
pub(crate) fn rejected_struct(item: &ItemStruct) -> TokenStream {
    let vis = &item.vis;
    let state = format_ident!("{}State", item.ident);
    let stub = stub_model_with(&item.ident, &state, &item.generics);
    quote! {
        #[doc(hidden)]
        #vis type #state = ::odyn::__private::RejectedState;
        #stub
    }
}

/// The `macro_rules!` that hands the struct to the impl block's expansion. On `Err` (the struct was
/// rejected) it hands over only the impl block, marked `!`, which comes back with odyn's method
/// attributes (`#[cell]`, `#[pair]`, `#[particle]`) removed and nothing added, so no follow-on
/// errors drown the real one.
pub(crate) fn forwarder(item: &ItemStruct, args: &TokenStream, ok: bool) -> TokenStream {
    let name = forwarder_name(&item.ident);
    let body = if ok {
        quote!(::odyn::__private::system_impl! { [#args] #item $($item)* })
    } else {
        quote!(::odyn::__private::system_impl! { ! $($item)* })
    };
    quote! {
        #[doc(hidden)]
        #[allow(unused_macros)]
        macro_rules! #name {
            ($($item:tt)*) => { #body };
        }
    }
}

/// The `Model` constants the attribute sets: `DEFAULT_METHOD`, `DEFAULT_DT`, `DEFAULT_RTOL`,
/// `DEFAULT_ATOL`. A value that is not a literal the macro could check (a `const`, an expression
/// of consts) is checked by a `const` assertion instead, so a zero or negative one is a compile
/// error at the user's tokens either way.
pub(crate) fn attribute_defaults(args: &Args) -> TokenStream {
    let method = match &args.integrator {
        Some((method, _)) => quote!(::odyn::Method::#method),
        None => quote!(::odyn::Method::Rk4),
    };
    let constant = |value: &Option<syn::Expr>, name: &str, zero_allowed: bool| match value {
        Some(expr) => {
            let message = if zero_allowed {
                format!("`{name}` in `#[system]` must be finite and non-negative")
            } else {
                format!("`{name}` in `#[system]` must be finite and positive")
            };
            let check = if zero_allowed {
                quote!(value >= 0.0)
            } else {
                quote!(value > 0.0)
            };
            quote_spanned! {expr.span()=>
                ::core::option::Option::Some({
                    let value = (#expr) as f64;
                    ::core::assert!(value.is_finite() && #check, #message);
                    value
                })
            }
        }
        None => quote!(::core::option::Option::None),
    };
    let (dt, rtol, atol) = (
        constant(&args.dt, "dt", false),
        constant(&args.rtol, "rtol", true),
        constant(&args.atol, "atol", true),
    );
    quote! {
        const DEFAULT_METHOD: ::odyn::Method = #method;
        const DEFAULT_DT: ::core::option::Option<f64> = #dt;
        const DEFAULT_RTOL: ::core::option::Option<f64> = #rtol;
        const DEFAULT_ATOL: ::core::option::Option<f64> = #atol;
    }
}
