//! Code generation shared by every model kind; the kinds' own `generate` files only say what
//! differs. Here: the forwarding macro between a struct's expansion and its impl block's, and
//! the stand-ins of a rejected model; in its modules:
//!
//! - [`model`]: the one `impl ::odyn::Model` builder (with the compile-time check of the
//!   attribute's constants);
//! - [`jacobian`]: what the `impl ::odyn::Jacobian` blocks share;
//! - [`hidden`]: derivatives → a hidden method of the model (the one step every kind takes);
//! - [`code`]: the expression graph as straight-line Rust, and [`prologue`], the user's
//!   state-free code that runs before it.
//!
//! Generated code names everything by absolute path (`::odyn::…`), binds the state to hygienic
//! locals, and documents every public item so `cargo doc` of a user's crate explains it.

mod code;
mod hidden;
mod jacobian;
mod model;
mod prologue;

use proc_macro2::{Span, TokenStream};
use quote::{format_ident, quote, quote_spanned};
use syn::ItemStruct;

pub(crate) use code::{lets, operand, straight_line};
pub(crate) use hidden::{evaluation, hidden_fn, time_copy};
pub(crate) use jacobian::{runtime_jacobian, time_independent};
pub(crate) use model::{ModelImpl, stub_model, stub_model_with};
pub(crate) use prologue::{opaques_read, prologue_tokens};

/// The name of the `macro_rules!` through which a struct's expansion reaches its impl block's.
///
/// rustc's own error when the impl's call finds no such macro — the struct lacks `#[system]`, or
/// comes after its impl, or lives in another module — cannot be replaced, so the name itself says
/// what is required: "cannot find macro `__odyn_requires_system_on_struct_Spring_above_this_impl`"
/// (a name that stays true in the notes of other errors, where the struct does have it).
/// What the struct's expansion tells the impl block's.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Forward {
    /// The struct was accepted: expand the model.
    Accepted,
    /// The struct was read, but its attribute arguments (or their fit with the integrator) were
    /// reported: expand the model all the same, with the default arguments, so code using it
    /// sees its real state type and draws no follow-on errors, and nothing of the arguments is
    /// evaluated or reported a second time.
    Reported,
    /// The struct was rejected: pass the impl block through, its bodies never run.
    Rejected,
}

pub(crate) fn forwarder_name(model: &syn::Ident) -> syn::Ident {
    format_ident!(
        "__odyn_requires_system_on_struct_{}_above_this_impl",
        model,
        span = model.span()
    )
}

/// For a struct `#[system]` rejected: its state type, as a type without values, and a stub
/// `Model` impl, so that uses of the model elsewhere in the crate (`model.simulate()`, the
/// state's name in signatures) type-check and the user sees the real error alone. Nothing of it
/// runs: the crate does not compile.
pub(crate) fn rejected_struct(item: &ItemStruct) -> TokenStream {
    let vis = &item.vis;
    let state = crate::model::state_ident(&item.ident);
    // A struct generic over lengths only keeps them on its state's name (`RodState<N>` in the
    // impl block draws no error of its own).
    let generics = &item.generics;
    let lengths_only = generics
        .params
        .iter()
        .all(|p| matches!(p, syn::GenericParam::Const(_)));
    let (alias, state_type) = if lengths_only && !generics.params.is_empty() {
        let (_, type_generics, _) = generics.split_for_impl();
        (quote!(#state #generics), quote!(#state #type_generics))
    } else {
        (quote!(#state), quote!(#state))
    };
    let stub = stub_model_with(&item.ident, state_type, generics);
    quote! {
        #[doc(hidden)]
        #vis type #alias = ::odyn::__private::RejectedState;
        #stub
    }
}

/// `imp` with the bodies of the methods `which` selects replaced by ones that never run: for a
/// rejected model, whose bodies read fields the stand-in state may not have as declared, or whose
/// errors rustc would report a second time.
pub(crate) fn never_run(
    mut imp: syn::ItemImpl,
    which: impl Fn(&syn::ImplItemFn) -> bool,
) -> syn::ItemImpl {
    for member in &mut imp.items {
        if let syn::ImplItem::Fn(f) = member
            && which(f)
        {
            f.attrs
                .push(syn::parse_quote!(#[allow(unused_variables, unreachable_code)]));
            f.block = syn::parse_quote!({
                ::core::unreachable!("odyn rejected this model at compile time")
            });
        }
    }
    imp
}

/// A check that the struct's impl block is marked `#[system]` too: only that attribute
/// implements `odyn::__private::SystemImpl`, whose `on_unimplemented` message then says, at the
/// struct's name, that the `#[system] impl` block is missing (rather than only rustc's "no
/// method named `simulate`" at a use). Not for a generic struct: its impl block may be for one
/// instance (`impl Chain<3>`), and the check cannot name which.
pub(crate) fn impl_check(item: &ItemStruct) -> TokenStream {
    if !item.generics.params.is_empty() {
        return TokenStream::new();
    }
    let ident = &item.ident;
    let is_model = format_ident!("__odyn_is_model", span = Span::mixed_site());
    let has_impl = format_ident!("__odyn_has_impl", span = Span::mixed_site());
    let checked = quote_spanned!(ident.span()=> #ident);
    quote! {
        const _: () = {
            fn #is_model<T: ::odyn::__private::SystemImpl + ?::core::marker::Sized>() {}
            #[allow(dead_code)]
            fn #has_impl() {
                #is_model::<#checked>();
            }
        };
    }
}

/// The `macro_rules!` that hands the struct to the impl block's expansion. On `Err` (the struct was
/// rejected) it hands over only the impl block, marked `!`, which comes back with odyn's method
/// attributes (`#[cell]`, `#[pair]`, `#[particle]`) removed and nothing added, so no follow-on
/// errors drown the real one.
pub(crate) fn forwarder(item: &ItemStruct, args: &TokenStream, forward: Forward) -> TokenStream {
    let name = forwarder_name(&item.ident);
    let body = match forward {
        Forward::Accepted => quote!(::odyn::__private::system_impl! { [#args] #item $($item)* }),
        Forward::Reported => quote!(::odyn::__private::system_impl! { [] #item $($item)* }),
        Forward::Rejected => quote!(::odyn::__private::system_impl! { ! $($item)* }),
    };
    quote! {
        #[doc(hidden)]
        #[allow(unused_macros)]
        macro_rules! #name {
            ($($item:tt)*) => { #body };
        }
    }
}
