//! Differential–algebraic fixed-size models, M·y′ = f(t, y): `#[algebraic]` fields, whose rows
//! of `derivative` are residuals 0 = g(t, y, z), and an optional constant `fn mass(&self) ->
//! [[f64; N]; N]`. What the macro refuses of them, and the `Model` items it generates.

use proc_macro2::TokenStream;
use quote::{ToTokens, quote, quote_spanned};
use syn::spanned::Spanned;
use syn::{FnArg, ImplItemFn, ItemStruct, ReturnType};

use crate::args::Args;
use crate::errors::Errors;
use crate::helpers::Helpers;
use crate::model::{Model, Role, StateField};
use crate::rewrite::rewrite;
use crate::syntax::{attribute, is_ref_self};

/// The `#[algebraic]` attribute of `field`, if it has one.
fn algebraic_attribute(field: &syn::Field) -> Option<&syn::Attribute> {
    attribute(&field.attrs, &["algebraic"])
}

/// Whether the `#[algebraic]` fields of `declared` are ones the macro takes: in a first-order
/// model (no `#[position]`/`#[velocity]` fields: a constrained mechanism is written in
/// first-order form) whose array lengths are integer literals. Reports each refusal at its
/// `#[algebraic]`.
pub(super) fn fields_accepted(
    declared: &[(StateField<'_>, &syn::Field)],
    second_order: usize,
    params: &[&syn::Ident],
    errors: &mut Errors,
) -> bool {
    let mut accepted = true;
    for (field, syn_field) in declared.iter().filter(|(f, _)| f.role == Role::Algebraic) {
        let at = match algebraic_attribute(syn_field) {
            Some(attr) => attr.to_token_stream(),
            None => field.ident.to_token_stream(),
        };
        if second_order > 0 {
            errors.at(
                at,
                format_args!(
                    "`#[algebraic]` field `{}` in a second-order model: algebraic components \
                     are for first-order models; write the system with `#[state]` fields \
                     (positions and velocities both) and `fn derivative`, whose rows of \
                     `#[algebraic]` fields are residuals 0 = g(t, y, z)",
                    field.ident
                ),
            );
            accepted = false;
        } else if !params.is_empty() {
            errors.at(
                at,
                "`#[algebraic]` fields need the state's layout at compile time: write the array \
                 lengths of this model as integer literals rather than const parameters",
            );
            accepted = false;
        }
    }
    accepted
}

/// Refuses `jacobian = false` on a model with `#[algebraic]` fields: consistent initial values
/// and the methods that take a mass matrix all solve with the Jacobian.
pub(super) fn args_accepted(item: &ItemStruct, args: &Args, errors: &mut Errors) {
    let Some(no_jacobian) = args.jacobian.off() else {
        return;
    };
    let first = item
        .fields
        .iter()
        .find_map(|f| algebraic_attribute(f).and(f.ident.as_ref()));
    if let Some(first) = first {
        errors.at(
            no_jacobian,
            format_args!(
                "`jacobian = false` leaves `#[algebraic]` `{first}` without the Jacobian its \
                 consistent initial value and the DAE methods (Rodas5P, Rosenbrock23, Bdf, ImplicitEuler) solve \
                 with; remove it (or use `jacobian = dual`)"
            ),
        );
    }
}

/// The component indices of the `#[algebraic]` fields, in the state's layout.
pub(super) fn indices(model: &Model<'_>) -> Vec<usize> {
    let mut at = 0;
    let mut indices = Vec::new();
    for field in &model.states {
        let len = field.shape.len();
        if field.role == Role::Algebraic {
            indices.extend(at..at + len);
        }
        at += len;
    }
    indices
}

/// Reads a first-order model's `fn mass(&self) -> [[f64; N]; N]`: no arguments but `&self`, a
/// return type, and no read of the state (M is constant). Reports what is wrong at its token.
pub(super) fn read_mass(
    f: &ImplItemFn,
    model: &Model<'_>,
    helpers: &Helpers,
    errors: &mut Errors,
) -> Option<ImplItemFn> {
    let before = errors.len();
    let sig = &f.sig;
    let mut inputs = sig.inputs.iter();
    match inputs.next() {
        Some(FnArg::Receiver(r)) if is_ref_self(r) => {}
        Some(other) => errors.at(other, "`mass` must take `&self`"),
        None => errors.at(&sig.ident, "`mass` must take `&self`"),
    }
    if let Some(extra) = inputs.next() {
        errors.at(
            extra,
            "the mass matrix is constant: `fn mass(&self) -> [[f64; N]; N]` takes no time or \
             state; a mass matrix that depends on them is not supported",
        );
    }
    if let ReturnType::Default = sig.output {
        errors.at(
            &sig.ident,
            format_args!(
                "`mass` must return the {n}×{n} mass matrix, `[[f64; {n}]; {n}]`, rows in the \
                 state's layout",
                n = model.len()
            ),
        );
    }
    let (_, reads) = rewrite(&f.block, model, helpers, &sig.ident, true, errors);
    if let Some((field, tokens)) = reads.iter().next() {
        errors.at(
            tokens,
            format_args!(
                "the mass matrix is constant: `fn mass` cannot read state `{field}`; a mass \
                 matrix that depends on the state is not supported"
            ),
        );
    }
    (errors.len() == before).then(|| f.clone())
}

/// Refuses a `fn residual`: a fully implicit model F(t, y, y′) = 0 is not supported.
pub(super) fn refuse_residual(f: &ImplItemFn, errors: &mut Errors) {
    errors.at(
        &f.sig.ident,
        "fully implicit models F(t, y, y′) = 0 are not supported: write M·y′ = f(t, y), with \
         `fn derivative` returning f, `#[algebraic]` fields for the algebraic equations (their \
         rows of `derivative` are residuals 0 = g) and `fn mass(&self) -> [[f64; N]; N]` for a \
         constant M that is not diagonal",
    );
}

/// The `Model` items of a differential–algebraic model (none for an ODE): `ALGEBRAIC`,
/// `MASS_MATRIX`, `mass` (from the user's `fn mass`, when defined) and `consistent`.
pub(super) fn model_items(
    model: &Model<'_>,
    mass: Option<&ImplItemFn>,
    state: &TokenStream,
) -> TokenStream {
    let algebraic = indices(model);
    if algebraic.is_empty() && mass.is_none() {
        return TokenStream::new();
    }
    let mass = mass.map(|f| {
        let n = model.len();
        let span = match &f.sig.output {
            ReturnType::Type(_, ty) => ty.span(),
            ReturnType::Default => f.sig.ident.span(),
        };
        // The type at the user's return type: a matrix of another size is an error there.
        let ty = quote_spanned!(span=> [[f64; #n]; #n]);
        quote! {
            fn mass(&self, state: &#state) -> ::odyn::Result<::odyn::Mass> {
                let rows: #ty = Self::mass(self);
                ::odyn::Mass::from_rows(
                    <Self as ::odyn::Model>::NAME,
                    &rows,
                    <Self as ::odyn::Model>::ALGEBRAIC,
                    state,
                )
            }
        }
    });
    let consistent = (!algebraic.is_empty()).then(|| {
        quote! {
            fn consistent(
                &self,
                t: f64,
                y: &mut #state,
                newton: &::odyn::NewtonOptions,
            ) -> ::odyn::Result<()> {
                ::odyn::consistent(self, t, y, newton)
            }
        }
    });
    quote! {
        const ALGEBRAIC: &'static [usize] = &[#(#algebraic),*];
        const MASS_MATRIX: bool = true;
        #mass
        #consistent
    }
}
