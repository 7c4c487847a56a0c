//! The `impl ::odyn::Model` of every model kind, and of the stand-in for a rejected one, built in
//! one place: what differs between kinds (how the state is gathered, the derivative and energy
//! computed, the state checked) comes in as methods; the associated types, the name, the
//! attribute's constants and their compile-time check are written here.

use proc_macro2::TokenStream;
use quote::{ToTokens, quote, quote_spanned};
use syn::spanned::Spanned;

use crate::args::Args;

/// One `impl ::odyn::Model`.
pub(crate) struct ModelImpl<'a> {
    /// The model's type as the impl names it, with its generic arguments (`Spring`, the user's
    /// `self_ty` such as `Chain<N>`).
    pub(crate) self_ty: TokenStream,
    /// The impl's generics: a const-generic model's (`<const N: usize>`), or a rejected generic
    /// struct's for its stand-in; empty otherwise.
    pub(crate) generics: &'a syn::Generics,
    /// The model's name (`Model::NAME`).
    pub(crate) name: String,
    /// `Model::State` (`SpringState`, `ChainState<N>`).
    pub(crate) state: TokenStream,
    /// The attribute's arguments, for `DEFAULT_METHOD`, `DEFAULT_DT`, `DEFAULT_RTOL` and
    /// `DEFAULT_ATOL`, whose values are also checked at compile time; `None` for a stand-in.
    pub(crate) args: Option<&'a Args>,
    /// `fn state`, `fn derivative` and `fn energy`, as the kind computes them.
    pub(crate) methods: TokenStream,
    /// Whether the model is its own `SecondOrder` (else `Unavailable`).
    pub(crate) second_order: bool,
    /// Whether the model is its own `Jacobian` (else `Unavailable`).
    pub(crate) jacobian: bool,
    /// The body of `fn check(&self, state)`, when the kind checks a state against the model.
    pub(crate) check: Option<TokenStream>,
}

impl<'a> ModelImpl<'a> {
    /// The impl of a model's runtime traits for its impl block `imp`, with the attribute's
    /// `args`: no methods yet, neither its own `SecondOrder` nor its own `Jacobian` (a kind sets
    /// what it has with struct update syntax).
    pub(crate) fn for_impl(
        imp: &'a syn::ItemImpl,
        model: &syn::Ident,
        state: TokenStream,
        args: &'a Args,
    ) -> Self {
        ModelImpl {
            self_ty: imp.self_ty.to_token_stream(),
            generics: &imp.generics,
            name: model.to_string(),
            state,
            args: Some(args),
            methods: TokenStream::new(),
            second_order: false,
            jacobian: false,
            check: None,
        }
    }

    /// The impl and, for a model with attribute arguments, a `const` that evaluates them, so a
    /// bad `dt` is an error even in a crate that never runs the model.
    pub(crate) fn build(self) -> TokenStream {
        let ModelImpl {
            self_ty,
            generics,
            name,
            state,
            args,
            methods,
            second_order,
            jacobian,
            check,
        } = self;
        let (impl_generics, _, where_clause) = generics.split_for_impl();
        let defaults = attribute_defaults(args.unwrap_or(&Args::default()));
        let (second_order_type, as_second_order) = optional_self(
            second_order,
            quote!(as_second_order),
            quote!(Self::SecondOrder),
        );
        let (jacobian_type, as_jacobian) =
            optional_self(jacobian, quote!(as_jacobian), quote!(Self::Jacobian));
        let check = check.map(|body| {
            quote! {
                fn check(&self, state: &#state) -> ::odyn::Result<()> {
                    #body
                }
            }
        });
        // A generic model's constants are evaluated where it is instantiated.
        let evaluated = args.filter(|_| generics.params.is_empty()).map(|_| {
            quote! {
                // Evaluates the attribute's constants here, so a bad `dt` is an error even in a
                // crate that never runs the model.
                const _: () = {
                    let _ = <#self_ty as ::odyn::Model>::DEFAULT_DT;
                    let _ = <#self_ty as ::odyn::Model>::DEFAULT_RTOL;
                    let _ = <#self_ty as ::odyn::Model>::DEFAULT_ATOL;
                };
            }
        });
        quote! {
            #[automatically_derived]
            impl #impl_generics ::odyn::Model for #self_ty #where_clause {
                type State = #state;
                type SecondOrder = #second_order_type;
                const NAME: &'static str = #name;
                #defaults
                #methods
                #as_second_order
                type Jacobian = #jacobian_type;
                #as_jacobian
                #check
            }
            #[automatically_derived]
            impl #impl_generics ::odyn::__private::Sealed for #self_ty #where_clause {}
            #evaluated
        }
    }
}

/// An associated type that is `Self` or `Unavailable<Self>`, and its accessor `method`.
fn optional_self(
    available: bool,
    method: TokenStream,
    assoc: TokenStream,
) -> (TokenStream, TokenStream) {
    if available {
        (
            quote!(Self),
            quote! {
                #[inline(always)]
                fn #method(&self) -> ::core::option::Option<&Self> {
                    ::core::option::Option::Some(self)
                }
            },
        )
    } else {
        (
            quote!(::odyn::__private::Unavailable<Self>),
            quote! {
                #[inline(always)]
                fn #method(&self) -> ::core::option::Option<&#assoc> {
                    ::core::option::Option::None
                }
            },
        )
    }
}

/// A `Model` impl for a model `#[system]` rejected: it is never run (the crate does not
/// compile), but with it the rest of the user's crate type-checks, so the user sees the real
/// error and not "no method named `simulate`" at every call site.
pub(crate) fn stub_model(model: &syn::Ident, state: &syn::Ident) -> TokenStream {
    stub_model_with(model, quote!(#state), &syn::Generics::default())
}

/// [`stub_model`] for a struct with `generics`, whose state type is `state` (`ChainState<N>`).
pub(crate) fn stub_model_with(
    model: &syn::Ident,
    state: TokenStream,
    generics: &syn::Generics,
) -> TokenStream {
    let never = quote!(::core::unreachable!(
        "odyn rejected this model at compile time"
    ));
    let (_, type_generics, _) = generics.split_for_impl();
    ModelImpl {
        self_ty: quote!(#model #type_generics),
        generics,
        name: model.to_string(),
        state: state.clone(),
        args: None,
        methods: quote! {
            fn state(&self) -> #state {
                #never
            }
            fn derivative(&self, _: f64, _: &#state, _: &mut #state) {
                #never
            }
            fn energy(&self, _: &#state) -> ::core::option::Option<f64> {
                #never
            }
        },
        second_order: false,
        jacobian: false,
        check: None,
    }
    .build()
}

/// The `Model` constants the attribute sets: `DEFAULT_METHOD`, `DEFAULT_DT`, `DEFAULT_RTOL`,
/// `DEFAULT_ATOL`. A value that is not a literal the macro could check (a `const`, an expression
/// of consts) is checked by a `const` assertion instead, so a zero or negative one is a compile
/// error at the user's tokens either way.
fn attribute_defaults(args: &Args) -> TokenStream {
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
