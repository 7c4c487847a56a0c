//! The one step from derivatives to code that every kind takes: a hidden method of the model
//! that copies the time, runs the user's state-free code the values need (the prologue), then
//! computes the derivatives as straight-line `let`s ([`super::code`]).

use proc_macro2::{Span, TokenStream};
use quote::{ToTokens, format_ident, quote};

use super::code::straight_line;
use super::prologue::{opaques_read, prologue_tokens};
use crate::ir::{ExprId, Graph};
use crate::lower::Prologue;

/// The time as derivative code reads it — a hygienic copy made before the prologue, which may
/// shadow the user's name (`let t = t - self.t0;`) — and the `let` making it; nothing when the
/// function takes no named time.
pub(crate) fn time_copy(time: Option<&syn::Ident>) -> (Option<TokenStream>, TokenStream) {
    let Some(t) = time else {
        return (None, TokenStream::new());
    };
    let copy = format_ident!("__odyn_time", span = Span::mixed_site());
    (Some(copy.to_token_stream()), quote!(let #copy: f64 = #t;))
}

/// What computes the nodes `roots` of `graph` (each state variable read as `components` names
/// it): the part of `prologue` they need, and their `let`s.
pub(crate) fn evaluation(
    graph: &Graph,
    roots: &[ExprId],
    components: &[TokenStream],
    prologue: &[Prologue],
) -> (Vec<TokenStream>, Vec<TokenStream>) {
    let lets = straight_line(graph, roots, components);
    (prologue_tokens(prologue, &opaques_read(graph, roots)), lets)
}

/// A hidden method `fn <signature> { <time copy> <prologue> <body> }`, allowed the lints that
/// generated straight-line code trips (unused values of a branch not taken, parentheses kept
/// for precedence, the user's non-snake-case names).
pub(crate) fn hidden_fn(
    signature: TokenStream,
    inline: TokenStream,
    time_copy: &TokenStream,
    prologue: &[TokenStream],
    body: TokenStream,
) -> TokenStream {
    quote! {
        #[doc(hidden)]
        #inline
        #[allow(
            unused_variables,
            unused_assignments,
            unused_mut,
            unused_parens,
            non_snake_case,
            clippy::all
        )]
        fn #signature {
            #time_copy
            #(#prologue)*
            #body
        }
    }
}
