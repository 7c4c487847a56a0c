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
//!
//! Before the kind is chosen, a field attribute a letter or two from one of odyn's (`#[feild]`)
//! is reported and read as the one it misses, so the kind is recognised and nothing else
//! follows from the typo; so is a kernel's method attribute (`#[cel]`).

pub(crate) mod fixed;
pub(crate) mod grid;
pub(crate) mod particles;

use proc_macro2::TokenStream;
use quote::quote;
use syn::{Attribute, ItemImpl, ItemStruct};

use crate::args::{self, Args};
use crate::errors::Errors;
use crate::generate;
use crate::syntax::{FIELD_ATTRIBUTES, RUST_ATTRIBUTES, strip_field_attributes};
use crate::validate::{self, FirstOrder};

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

/// What a front-end makes of a struct it accepts.
pub(crate) struct Struct {
    /// The state type `<Model>State` and its impls.
    pub(crate) state: TokenStream,
    /// `Some` for a first-order model: how to say so when the integrator needs a second-order one.
    pub(crate) first_order: Option<FirstOrder>,
}

/// The struct half of `#[system]`: the struct without odyn's attributes, its state type, and the
/// forwarding macro to the impl block (which passes the impl block through untouched when the
/// struct was rejected).
pub(crate) fn expand_struct(args_tokens: TokenStream, item: &ItemStruct) -> TokenStream {
    let mut errors = Errors::default();
    let args = args::parse(args_tokens.clone(), &mut errors);
    let item = &unknown_attributes(item, &mut errors);
    let stripped = strip_field_attributes(item);
    let state = if is_generic(item) {
        // One error: the fields of a generic model (`[f64; N]`, `k: T`) would each be refused
        // only because of the generics.
        errors.at(
            &item.generics,
            "generic models are not supported: `#[system]` lays out the state and derives its \
             Jacobian for one concrete struct; write array lengths as integer literals \
             (`[f64; 3]`) and parameters as `f64` fields",
        );
        validate::structure(&args, None, &mut errors);
        None
    } else {
        let accepted = match Kind::of(item) {
            Kind::Fixed => fixed::expand_struct(item, &mut errors),
            Kind::Particles => particles::expand_struct(item, &mut errors),
            Kind::Grid => grid::expand_struct(item, &mut errors),
        };
        let first_order = accepted.as_ref().and_then(|s| s.first_order.as_ref());
        validate::structure(&args, first_order, &mut errors);
        accepted.map(|s| s.state)
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

/// Whether the struct has generic parameters or a `where` clause.
fn is_generic(item: &ItemStruct) -> bool {
    !item.generics.params.is_empty() || item.generics.where_clause.is_some()
}

/// The impl half, with the struct: the runtime trait impls of the struct's kind.
pub(crate) fn expand_impl(args: &Args, item: &ItemStruct, imp: &ItemImpl) -> TokenStream {
    let kind = Kind::of(item);
    let mut errors = Errors::default();
    let imp = &unknown_method_attributes(kind, imp, &mut errors);
    let expanded = match kind {
        Kind::Fixed => fixed::expand_impl(args, item, imp),
        Kind::Particles => particles::expand_impl(args, item, imp),
        Kind::Grid => grid::expand_impl(args, item, imp),
    };
    // The kind read a near miss as the attribute meant: its expansion stands beside the error.
    let error = errors.finish().err().map(|e| e.to_compile_error());
    quote!(#expanded #error)
}

/// Reports each field attribute that is neither odyn's nor Rust's: a near miss of one of odyn's
/// (`#[feild]`), or any other when nothing on the struct (a derive, an attribute macro) could
/// own it as a helper. Returns the struct with each near miss read as the attribute it misses, so
/// the kind is recognised and nothing else follows from the typo, and the others removed, so
/// rustc does not report them a second time.
fn unknown_attributes(item: &ItemStruct, errors: &mut Errors) -> ItemStruct {
    let helpers_possible = item.attrs.iter().any(|a| {
        !a.path()
            .get_ident()
            .is_some_and(|i| RUST_ATTRIBUTES.contains(&i.to_string().as_str()))
    });
    let mut item = item.clone();
    for field in &mut item.fields {
        check_attributes(
            &mut field.attrs,
            &FIELD_ATTRIBUTES,
            !helpers_possible,
            errors,
        );
    }
    item
}

/// The same for the methods of a grid's or particle model's impl block, whose kernels odyn
/// finds by attribute (`#[cell]`, `#[pair]`, `#[particle]`): near misses are reported and read
/// as meant. Other attributes may be any attribute macro's.
fn unknown_method_attributes(kind: Kind, imp: &ItemImpl, errors: &mut Errors) -> ItemImpl {
    let known: &[&str] = match kind {
        Kind::Fixed => return imp.clone(),
        Kind::Grid => &["cell"],
        Kind::Particles => &["pair", "particle"],
    };
    let mut imp = imp.clone();
    for member in &mut imp.items {
        if let syn::ImplItem::Fn(f) = member {
            check_attributes(&mut f.attrs, known, false, errors);
        }
    }
    imp
}

/// Reports the attributes of `attrs` that are neither odyn's (`known`) nor Rust's and are at
/// most two edits from one of `known`, or, if `strict`, any such: a near miss becomes the
/// attribute it misses, any other is removed.
fn check_attributes(attrs: &mut Vec<Attribute>, known: &[&str], strict: bool, errors: &mut Errors) {
    attrs.retain_mut(|attr| {
        let Some(ident) = attr.path().get_ident().cloned() else {
            return true;
        };
        let name = ident.to_string();
        if known.contains(&name.as_str()) || RUST_ATTRIBUTES.contains(&name.as_str()) {
            return true;
        }
        let Some((distance, nearest)) = known
            .iter()
            .map(|&k| (edit_distance(&name, k), k))
            .min_by_key(|&(distance, _)| distance)
        else {
            return true;
        };
        let near_miss = distance <= 2;
        if !near_miss && !strict {
            return true;
        }
        // The one it nearly is first, then the others in their order.
        let mut expected = known.to_vec();
        if near_miss {
            expected.retain(|&k| k != nearest);
            expected.insert(0, nearest);
        }
        let expected: Vec<String> = expected.iter().map(|k| format!("`{k}`")).collect();
        let expected = match expected.as_slice() {
            [one] => one.clone(),
            many => format!("one of {}", many.join(", ")),
        };
        errors.at(
            &*attr,
            format_args!("unknown attribute `{name}`; expected {expected}"),
        );
        if near_miss {
            let path = match &mut attr.meta {
                syn::Meta::Path(path) => path,
                syn::Meta::List(list) => &mut list.path,
                syn::Meta::NameValue(pair) => &mut pair.path,
            };
            *path = syn::Ident::new(nearest, ident.span()).into();
        }
        near_miss
    });
}

/// Edits (insertions, deletions, substitutions, swaps of neighbours) that turn `a` into `b`,
/// letters compared without case.
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.to_lowercase().chars().collect();
    let b: Vec<char> = b.to_lowercase().chars().collect();
    // d[i][j]: edits from a[..i] to b[..j].
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let substitution = usize::from(a[i - 1] != b[j - 1]);
            let mut best = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + substitution);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                best = best.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = best;
        }
    }
    d[a.len()][b.len()]
}

#[cfg(test)]
mod tests {
    use super::edit_distance;

    #[test]
    fn edit_distances() {
        assert_eq!(edit_distance("feild", "field"), 1);
        assert_eq!(edit_distance("postion", "position"), 1);
        assert_eq!(edit_distance("Mass", "mass"), 0);
        assert_eq!(edit_distance("velocty", "velocity"), 1);
        assert_eq!(edit_distance("pin", "pinned"), 3);
        assert_eq!(edit_distance("serde", "state"), 3);
    }
}
