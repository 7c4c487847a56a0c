//! What the fixed-size front-end's code generators share: how big a "small" model is, how the
//! state reaches a re-emitted function (its parameters and components), and a generated
//! Jacobian's body. Its own module so `generate`, `jacobian` and `tangent` each import it and
//! none of them imports another for these.

use proc_macro2::TokenStream;
use quote::quote;

use super::functions::Function;
use crate::ir::ExprId;
use crate::model::{Model, Shape};
use crate::rewrite::state_local;

/// Models with at most this many state components get a stack `SMatrix` Jacobian; larger ones a
/// heap `FaerDense`, solved with faer.
pub(super) const SMALL: usize = 32;

/// A Jacobian's generated body: its statements (writing the matrix), its structural non-zeros,
/// in the order the statements rely on, and the graph nodes whose values it writes.
pub(super) struct JacobianBody {
    pub(crate) statements: TokenStream,
    pub(crate) nonzeros: Vec<(usize, usize)>,
    pub(crate) reads: Vec<ExprId>,
}

/// The inlining of a hidden function of `model`: a hint when small, never when big, so a big
/// body is compiled once rather than into every stage of every integrator; the compiler's
/// choice when the size is a const parameter.
pub(super) fn inline_hint(model: &Model<'_>, small: TokenStream) -> TokenStream {
    if model.is_generic() {
        quote!(#[inline])
    } else if model.len() <= SMALL {
        small
    } else {
        quote!(#[inline(never)])
    }
}

/// The time parameter of a re-emitted function: the user's own (`t: f64`), or an unused one.
pub(super) fn time_param(f: &Function) -> TokenStream {
    match &f.time {
        Some(t) => quote!(#t),
        None => quote!(_: f64),
    }
}

/// The state fields as parameters of a re-emitted function, bound to hygienic locals: a scalar
/// by value, an array or vector by reference (the rewritten body reads it as `(*local)`; see
/// [`crate::rewrite::rewrite`]), so evaluating f copies no state.
pub(super) fn state_params<'a>(model: &'a Model<'_>) -> impl Iterator<Item = TokenStream> + 'a {
    model.states.iter().map(|s| {
        let local = state_local(s.ident);
        let ty = model.type_of(s.shape);
        match s.shape {
            Shape::Scalar => quote!(#local: #ty),
            Shape::Array(_) | Shape::Vector(_) | Shape::Rows(..) => quote!(#local: &#ty),
        }
    })
}

/// The arguments matching [`state_params`], read from the state `from`.
pub(super) fn state_args<'a>(
    model: &'a Model<'_>,
    from: &'a syn::Ident,
) -> impl Iterator<Item = TokenStream> + 'a {
    model.states.iter().map(move |s| {
        let field = s.ident;
        match s.shape {
            Shape::Scalar => quote!(#from.#field),
            Shape::Array(_) | Shape::Vector(_) | Shape::Rows(..) => quote!(&#from.#field),
        }
    })
}

/// How each state component is read inside the generated Jacobian function.
pub(super) fn component_tokens(model: &Model<'_>) -> Vec<TokenStream> {
    model
        .states
        .iter()
        .flat_map(|f| {
            let local = state_local(f.ident);
            f.shape.component_reads(&quote!(#local))
        })
        .collect()
}
