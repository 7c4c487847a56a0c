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
//! Adding a kind is adding a directory here with `expand_struct` and `expand_impl`, a variant of
//! [`Kind`] that recognises its struct, and its runtime module.

pub(crate) mod fixed;
pub(crate) mod grid;
pub(crate) mod particles;

use proc_macro2::TokenStream;
use quote::quote;
use syn::{ItemImpl, ItemStruct};

use crate::args::{self, Args};
use crate::errors::Errors;
use crate::generate;

/// The kind of a model struct.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    Fixed,
    Particles,
    Grid,
}

impl Kind {
    /// The kind `item` declares by its attributes: `#[mass]`, `#[pinned]` or `Vec` positions
    /// make particles, `#[field]` grids, anything else a fixed-size model.
    pub(crate) fn of(item: &ItemStruct) -> Kind {
        if particles::is_particle_model(item) {
            Kind::Particles
        } else if grid::is_grid_model(item) {
            Kind::Grid
        } else {
            Kind::Fixed
        }
    }
}

/// The struct half of `#[system]`: the struct without odyn's attributes, its state type, and the
/// forwarding macro to the impl block (which passes the impl block through untouched when the
/// struct was rejected).
pub(crate) fn expand_struct(args_tokens: TokenStream, item: &ItemStruct) -> TokenStream {
    let mut errors = Errors::default();
    let args = args::parse(args_tokens.clone(), &mut errors);
    let (stripped, state) = match Kind::of(item) {
        Kind::Fixed => fixed::expand_struct(item, &args, &mut errors),
        Kind::Particles => particles::expand_struct(item, &mut errors),
        Kind::Grid => grid::expand_struct(item, &mut errors),
    };
    match (errors.finish(), state) {
        (Ok(()), Some(state)) => {
            let forwarder = generate::forwarder(item, &args_tokens, true);
            quote!(#stripped #state #forwarder)
        }
        (result, _) => {
            let error = result.err().map(|e| e.to_compile_error());
            let forwarder = generate::forwarder(item, &args_tokens, false);
            let stub = generate::rejected_struct(item);
            quote!(#stripped #error #forwarder #stub)
        }
    }
}

/// The impl half, with the struct: the runtime trait impls of the struct's kind.
pub(crate) fn expand_impl(args: &Args, item: &ItemStruct, imp: &ItemImpl) -> TokenStream {
    match Kind::of(item) {
        Kind::Fixed => fixed::expand_impl(args, item, imp),
        Kind::Particles => particles::expand_impl(args, item, imp),
        Kind::Grid => grid::expand_impl(args, item, imp),
    }
}
