//! The `#[system]` attribute of odyn: one pipeline of small stages, with a front-end per model
//! kind.
//!
//! ```text
//!   #[system] struct / impl ──► expand ──► args (each argument read once, every error kept)
//!        ─► kinds: the FrontEnd of the struct's kind (one row of kinds::KINDS) reads the
//!           struct and the functions, reporting what it rejects at its token
//!        ─► validate (what the integrator asks: order, velocity-free forces, the Jacobian)
//!        ─► model (state description) ─► helpers (#[odyn::function] methods)
//!        ─► rewrite (self.x → state locals) ─► unroll (literal-range loops, in emitted code)
//!        ─► lower (body → expression graph, ir; helpers inlined, loops on the state unrolled)
//!        ─► derivative / sparsity (∂f, pattern)
//!        ─► generate: hidden (derivatives → hidden methods: code, prologue), model (the one
//!           impl Model) ─► the kind's generate (its runtime trait impls)
//!   rejected anywhere: the item, the errors, and stand-ins (kinds::expand_impl, one path)
//! ```
//!
//! Shared stages, one file or directory each, that know nothing of the kinds:
//!
//! - `args`: the attribute's arguments (`integrator`, `dt`, `rtol`, `atol`, `jacobian`);
//! - `validate`: what the attribute's integrator asks of the model (its order, velocity-free
//!   forces, the Jacobian, tolerances), checked once for every kind;
//! - `model`: the state description a front-end builds — fields, roles, shapes;
//! - `helpers`: the model's helper functions, methods marked `#[odyn::function]`, which `lower`
//!   inlines where they are called;
//! - `rewrite`: function bodies with every read of state made explicit;
//! - `unroll`: `for` loops over literal ranges copied out in the code emitted for a function,
//!   so every index is a constant;
//! - `lower`: a body to the expression graph `ir` (`lower` for a whole-state function,
//!   `lower_kernel` for a kernel of its arguments);
//! - `derivative`, `sparsity`: exact derivatives and structural patterns of the graph (pure: no
//!   syn, no quote);
//! - `generate`: the forwarding macro, the stand-ins of a rejected model, the one
//!   `impl ::odyn::Model` builder, the derivative-to-hidden-method step, and the graph as
//!   straight-line code;
//! - `syntax`: the names odyn gives meaning to, and the type and attribute questions every
//!   stage asks;
//! - `errors`, `limits`: every problem reported at its own token; inputs too deep to expand.
//!
//! Model kinds, under `kinds/` (see its module docs for adding one): `fixed` (fixed-size
//! first- and second-order models), `particles` (`Vec` positions with pair and particle
//! kernels), `grid` (`#[field]` grids with a `#[cell]` stencil kernel). Each is a `FrontEnd`
//! (its struct and impl block read) with its own `generate` for the runtime trait impls of its
//! `odyn` module.
//!
//! `expand` wires the two halves together: the struct's expansion defines a `macro_rules!`
//! carrying the struct's tokens to the impl block's expansion, the one place that sees both.

mod args;
mod derivative;
mod errors;
mod expand;
mod generate;
mod helpers;
mod ir;
mod kinds;
mod limits;
mod lower;
mod math;
mod model;
mod rewrite;
mod sparsity;
mod syntax;
mod unroll;
mod validate;

use proc_macro::TokenStream;

/// *`odyn-macros` defines this attribute for the `odyn` crate, which re-exports it as
/// `odyn::system` and documents it there (the code it generates names `odyn`'s items).*
#[proc_macro_attribute]
pub fn system(args: TokenStream, item: TokenStream) -> TokenStream {
    expand::system(args.into(), item.into()).into()
}

/// *`odyn-macros` defines this attribute for the `odyn` crate, which re-exports it as
/// `odyn::function` and documents it there.*
#[proc_macro_attribute]
pub fn function(args: TokenStream, item: TokenStream) -> TokenStream {
    expand::function(args.into(), item.into()).into()
}

/// The second half of `#[system]`: receives the struct (forwarded by a `macro_rules!` the struct
/// expansion defined) together with the impl block. Not a public API.
#[doc(hidden)]
#[proc_macro]
pub fn __system_impl(input: TokenStream) -> TokenStream {
    expand::system_impl(input.into()).into()
}
