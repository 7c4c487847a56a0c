//! The field (grid) model front-end: `#[field]` grids and one `#[cell]` kernel.
//!
//! The struct gives the fields ([`parse_struct`]); the impl block gives the kernel
//! ([`cell`]), whose stencil reads `u.e` are renamed to scalar inputs `u__e` ([`reads`]) so
//! the shared [`crate::lower::lower_kernel`] sees a function of numbers; [`generate`] emits its
//! derivative blocks and the runtime trait impls, which leave the loops over cells and the
//! assembly to `odyn::grid`.

mod cell;
mod generate;
mod reads;

use proc_macro2::TokenStream;
use quote::quote;
use syn::{Ident, ItemImpl, ItemStruct};

use cell::parse_cell;

use crate::args::Args;
use crate::errors::Errors;
use crate::kinds::{FrontEnd, Impl, Struct};
use crate::lower;
use crate::model::{Model, Order, Role, Shape, StateField, state_ident};
use crate::syntax::{attribute, has_attribute, names_type, no_arguments};
use crate::validate::FirstOrder;

/// The names of a stencil's neighbours, in the runtime's order (`odyn::grid::NEIGHBOURS`).
pub(crate) const NEIGHBOURS: [&str; 9] = ["c", "e", "w", "n", "s", "ne", "nw", "se", "sw"];

/// A field model's struct.
pub(crate) struct Fields<'a> {
    pub(crate) item: &'a ItemStruct,
    /// The `#[field]` grids, in declaration order.
    pub(crate) fields: Vec<&'a Ident>,
    /// The other `Grid` fields: coefficient grids, parameters read through a stencil.
    pub(crate) coefficients: Vec<&'a Ident>,
    /// The `#[algebraic]` fields, by index in [`Fields::fields`]: their rows of the cell method
    /// are residuals 0 = g, and the model is M·y′ = f with M zero in their rows.
    pub(crate) algebraic: Vec<usize>,
}

impl Fields<'_> {
    fn state_ident(&self) -> Ident {
        state_ident(&self.item.ident)
    }

    /// The model as the body rewriter sees it: the grids are state (read only through
    /// stencils).
    fn rewriter_model(&self) -> Model<'_> {
        Model {
            item: self.item,
            order: Order::First,
            states: self
                .fields
                .iter()
                .map(|&ident| StateField {
                    ident,
                    role: Role::State,
                    shape: Shape::Scalar,
                })
                .collect(),
            params: Vec::new(),
        }
    }
}

/// Whether `item` is a field model: it has a `#[field]` field.
pub(crate) fn is_grid_model(item: &ItemStruct) -> bool {
    item.fields.iter().any(|f| has_attribute(&f.attrs, "field"))
}

/// Reads a field model's struct, reporting every problem to `errors`.
pub(crate) fn parse_struct<'a>(item: &'a ItemStruct, errors: &mut Errors) -> Option<Fields<'a>> {
    let mut fields = Vec::new();
    let mut coefficients = Vec::new();
    let mut algebraic = Vec::new();
    for field in &item.fields {
        // Refused before the front-end with its own error (`kinds::expand_struct`).
        let ident = field.ident.as_ref()?;
        for attr in &field.attrs {
            let other = ["state", "position", "velocity", "mass", "pinned"];
            if other.iter().any(|n| attr.path().is_ident(n)) {
                errors.at(
                    attr,
                    "a field model's state is its `#[field]` grids (`odyn::grid::Grid`); other \
                     state attributes cannot be mixed with them",
                );
            }
        }
        let algebraic_attr = attribute(&field.attrs, &["algebraic"]);
        let Some(attr) = attribute(&field.attrs, &["field"]) else {
            if let Some(attr) = algebraic_attr {
                let message = match names_type(&field.ty, "Grid") {
                    true => {
                        "an algebraic grid is a field of the state: write \
                             `#[field] #[algebraic]` (its rows of the `#[cell]` method are \
                             residuals 0 = g)"
                    }
                    false => {
                        "`#[algebraic]` in a field model marks a `#[field]` grid whose rows \
                              of the `#[cell]` method are residuals 0 = g; this field is not a \
                              grid but a parameter"
                    }
                };
                errors.at(attr, message);
            } else if names_type(&field.ty, "Grid") {
                coefficients.push(ident);
            }
            continue;
        };
        if let Some(attr) = algebraic_attr {
            no_arguments(attr, "`#[algebraic]` takes no arguments", errors);
            algebraic.push(fields.len());
        }
        no_arguments(
            attr,
            "`#[field]` takes no arguments; the boundary is part of the grid: \
             `Grid::new(nx, ny, Boundary::Periodic, values)`",
            errors,
        );
        if !names_type(&field.ty, "Grid") {
            errors.at(
                &field.ty,
                "a `#[field]` must be an `odyn::grid::Grid` (values on an nx × ny grid with a \
                 boundary)",
            );
        }
        fields.push(ident);
    }
    Some(Fields {
        item,
        fields,
        coefficients,
        algebraic,
    })
}

/// The state type of a field model: an alias of the runtime's.
pub(crate) fn state(fields: &Fields<'_>) -> TokenStream {
    let vis = &fields.item.vis;
    let name = fields.state_ident();
    let doc = format!(
        "The state of [`{}`], generated by `#[system]`: the values of every `#[field]` grid, one \
         field after another.",
        fields.item.ident
    );
    quote! {
        #[doc = #doc]
        #vis type #name = ::odyn::grid::GridState;
    }
}

/// The field-model front-end: structs with `#[field]` grids.
pub(crate) struct Kind;

impl FrontEnd for Kind {
    fn recognises(&self, item: &ItemStruct) -> bool {
        is_grid_model(item)
    }

    fn method_attributes(&self) -> &'static [&'static str] {
        &["cell"]
    }

    /// The struct half: the state type, and what the model asks of an integrator, when accepted.
    fn expand_struct(&self, args: &Args, item: &ItemStruct, errors: &mut Errors) -> Option<Struct> {
        let fields = parse_struct(item, errors)?;
        if let (Some(no_jacobian), Some(&first)) = (args.jacobian.off(), fields.algebraic.first()) {
            errors.at(
                no_jacobian,
                format_args!(
                    "`jacobian = false` leaves `#[algebraic]` `{}` without the Jacobian its \
                     consistent initial value and the DAE methods (Rodas5P, Rosenbrock23, Bdf, \
                     ImplicitEuler) solve with; remove it",
                    fields.fields[first]
                ),
            );
        }
        Some(Struct {
            state: state(&fields),
            first_order: Some(FirstOrder {
                second_order: "positions and velocities",
                model: format!("field model `{}` is first-order", item.ident),
                instead: "`ExplicitEuler`, `Rk4`, `ImplicitEuler` or `Rodas5P`",
            }),
        })
    }

    /// The impl block of a field model: the cell kernel → blocks → runtime trait impls.
    fn expand_impl(
        &self,
        args: &Args,
        item: &ItemStruct,
        imp: &ItemImpl,
        errors: &mut Errors,
    ) -> Impl {
        let Some(fields) = parse_struct(item, errors) else {
            return Impl::Rejected {
                silenced: None,
                stand_ins: TokenStream::new(),
            };
        };
        // Lowered only when nothing was reported, a helper's problem included.
        let helpers = crate::helpers::parse(imp, &fields.rewriter_model(), errors);
        let cell = parse_cell(imp, &fields, errors);
        let mut lowered = None;
        let mut misread = false;
        if let Some(cell) = &cell {
            let name = &cell.f.sig.ident;
            let (_, state_reads) = crate::rewrite::rewrite(
                &cell.f.block,
                &fields.rewriter_model(),
                &helpers,
                name,
                false,
                errors,
            );
            if let Some(tokens) = state_reads.values().next() {
                errors.at(
                    tokens,
                    format_args!(
                        "`{name}` reads the grids only through its stencil arguments, not through \
                         `self`"
                    ),
                );
            }
            let inputs: Vec<Ident> = cell
                .stencils
                .iter()
                .flat_map(|(s, _)| NEIGHBOURS.map(|n| reads::input(s, n)))
                .collect();
            let before = errors.len();
            let renamed = reads::rename(&cell.f, &cell.stencils, errors);
            misread = errors.len() > before;
            if args.jacobian.off().is_none() && errors.is_empty() {
                let model = Model::parameters(fields.item, Order::First);
                let outputs = fields.fields.len();
                match lower::lower_kernel(
                    &model,
                    &helpers,
                    &renamed,
                    &inputs,
                    1,
                    outputs,
                    cell.time.clone(),
                ) {
                    Ok(l) => lowered = Some(l),
                    Err(error) => errors.push(error),
                }
            }
        }
        match cell {
            Some(cell) if errors.is_empty() => {
                Impl::Accepted(generate::impls(&fields, args, &cell, imp, lowered))
            }
            // A misread stencil (`u.nn`, `u.gradient()`) is also an error of rustc's in the
            // user's own body: emitted as written, it would be reported twice.
            cell => Impl::Rejected {
                silenced: cell.filter(|_| misread).map(|c| c.f.sig.ident),
                stand_ins: TokenStream::new(),
            },
        }
    }
}
