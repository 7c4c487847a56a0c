//! What the kinds' `impl ::odyn::Jacobian` blocks share: ∂f/∂t when f does not read the time,
//! and the whole impl for a kind whose runtime module assembles the matrix from generated blocks.

use proc_macro2::{Span, TokenStream};
use quote::quote;

/// The `Jacobian` items of an f that does not read the time: ∂f/∂t = 0, known at compile time.
/// `why` is the doc's sentence, such as "Kernels do not read the time".
pub(crate) fn time_independent(state: &impl quote::ToTokens, why: &str) -> TokenStream {
    let doc = format!(" {why}: ∂f/∂t = 0.");
    quote! {
        #[doc = #doc]
        const TIME_DEPENDENT: bool = false;
        #[inline]
        fn time_derivative(&self, _: f64, _: &#state, dfdt: &mut #state) {
            ::odyn::State::as_mut_slice(dfdt).fill(0.0);
        }
    }
}

/// The `impl ::odyn::Jacobian` of a kind whose runtime module (`module`: `particles`, `grid`)
/// assembles the sparse `matrix` at run time, so its structural pattern is not a constant
/// (`pattern` says where it comes from); `time` are its ∂f/∂t items.
pub(crate) fn runtime_jacobian(
    self_ty: &syn::Type,
    state: &syn::Ident,
    module: &str,
    matrix: TokenStream,
    pattern: &str,
    time: TokenStream,
) -> TokenStream {
    let module = syn::Ident::new(module, Span::call_site());
    let doc = format!(" Empty: {pattern}.");
    quote! {
        #[automatically_derived]
        impl ::odyn::Jacobian for #self_ty {
            type Matrix = #matrix;
            #[doc = #doc]
            const NONZEROS: &'static [(usize, usize)] = &[];
            fn jacobian_matrix(&self, state: &#state) -> Self::Matrix {
                ::odyn::__private::#module::jacobian_matrix(self, state)
            }
            #[inline]
            fn jacobian(&self, t: f64, y: &#state, jacobian: &mut Self::Matrix) {
                ::odyn::__private::#module::jacobian(self, t, y, jacobian)
            }
            #time
        }
    }
}
