//! The `#[system]` attribute of odyn: a shim that hands `proc_macro2` tokens to `expand`.
//!
//! The pipeline, one file a stage: `args` (the attribute's arguments) → `model` (the struct:
//! state fields, their roles and shapes) → `functions` (the impl block: the force, derivative
//! and energy bodies, with state reads made explicit) → `lower` (the force body as an
//! expression graph, `ir`) → `derivative` (its exact Jacobian, pure: no syn, no quote) →
//! `generate` (the state type, the Jacobian as straight-line code, the runtime trait impls).
//! `particles` runs the same stages per force kernel for particle models. `expand` wires them
//! together; `errors` collects every problem so a user sees all of them at once, each at its own
//! token.

mod args;
mod derivative;
mod errors;
mod expand;
mod functions;
mod generate;
mod ir;
mod kinds;
mod limits;
mod lower;
mod model;
mod particles;
mod sparsity;
mod tangent;

use proc_macro::TokenStream;

/// Declares an odyn model: on a struct it generates the typed state; on the struct's impl block it
/// reads the force (or derivative) and energy functions and implements the runtime traits.
///
/// See the `odyn` crate's documentation for the full syntax.
#[proc_macro_attribute]
pub fn system(args: TokenStream, item: TokenStream) -> TokenStream {
    expand::system(args.into(), item.into()).into()
}

/// The second half of `#[system]`: receives the struct (forwarded by a `macro_rules!` the struct
/// expansion defined) together with the impl block. Not a public API.
#[doc(hidden)]
#[proc_macro]
pub fn __system_impl(input: TokenStream) -> TokenStream {
    expand::system_impl(input.into()).into()
}
