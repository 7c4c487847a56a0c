//! Code generation for field models: the cell kernel's derivative blocks as straight-line code,
//! and the `GridSystem`, `Model` and `Jacobian` impls, which call into `odyn::grid`.

use proc_macro2::{Literal, Span, TokenStream};
use quote::{format_ident, quote};
use syn::ItemImpl;

use super::cell::{Argument, Cell};
use super::{Fields, NEIGHBOURS};
use crate::args::Args;
use crate::derivative::Differentiator;
use crate::generate::{
    ModelImpl, evaluation, hidden_fn, operand, runtime_jacobian, time_copy, time_independent,
};
use crate::lower::Lowered;

/// The runtime trait impls of a field model; `lowered` is the cell kernel, absent with
/// `jacobian = false`.
pub(super) fn impls(
    fields: &Fields<'_>,
    args: &Args,
    cell: &Cell,
    imp: &ItemImpl,
    lowered: Option<Lowered>,
) -> TokenStream {
    let self_ty = &imp.self_ty;
    let state = fields.state_ident();
    let count = Literal::usize_unsuffixed(fields.fields.len());
    let grids = &fields.fields;
    let names: Vec<String> = grids.iter().map(ToString::to_string).collect();
    // The coefficient grids the cell reads (others are plain parameters, never checked).
    let coefficients: Vec<_> = cell
        .arguments
        .iter()
        .filter_map(|argument| match *argument {
            Argument::Coefficient(k) => Some(fields.coefficients[k]),
            _ => None,
        })
        .collect();
    let coefficient_names: Vec<String> = coefficients.iter().map(ToString::to_string).collect();
    let kernel = &cell.f.sig.ident;
    let arguments: Vec<TokenStream> = cell
        .arguments
        .iter()
        .map(|argument| match *argument {
            Argument::Stencil(index) => {
                let index = Literal::usize_unsuffixed(index);
                quote!(stencils[#index])
            }
            Argument::Coefficient(k) => {
                let grid = fields.coefficients[k];
                quote!(::odyn::__private::grid::coefficient(&self.#grid, at))
            }
            Argument::X => quote!(at.x),
            Argument::Y => quote!(at.y),
            Argument::T => quote!(at.t),
        })
        .collect();
    let rate = if cell.scalar {
        quote!([self.#kernel(#(#arguments),*)])
    } else {
        quote!(self.#kernel(#(#arguments),*))
    };
    let zeros = quote!([0.0; #count]);
    let has_jacobian = lowered.is_some();
    let (blocks, jacobian_fn, jacobian_call, time_call, jacobian_impl) = match lowered {
        Some(lowered) => {
            let Generated {
                blocks,
                function,
                time,
            } = blocks(cell, lowered);
            let hidden = hidden_name(cell);
            let (time_call, time_items) = match time {
                Time::Exact => {
                    let hidden = time_name(cell);
                    (
                        quote!(self.#hidden(#(#arguments),*)),
                        quote! {
                            /// The `#[cell]` method reads the time: ∂f/∂t of every cell,
                            /// generated.
                            const TIME_DEPENDENT: bool = true;
                            #[inline]
                            fn time_derivative(&self, t: f64, y: &#state, dfdt: &mut #state) {
                                ::odyn::__private::grid::time_derivative(self, t, y, dfdt)
                            }
                        },
                    )
                }
                // The time reaches the rate through code odyn cannot differentiate: the
                // runtime's central difference.
                Time::Opaque => (
                    zeros.clone(),
                    quote!(
                        const TIME_DEPENDENT: bool = true;
                    ),
                ),
                Time::Unread => (
                    zeros.clone(),
                    time_independent(&state, "A cell's rate does not read the time"),
                ),
            };
            (
                blocks,
                function,
                quote!(blocks.copy_from_slice(&self.#hidden(#(#arguments),*));),
                time_call,
                runtime_jacobian(
                    self_ty,
                    &state,
                    "grid",
                    quote!(::odyn::grid::GridJacobian),
                    "a field model's pattern comes from its grid at run time",
                    time_items,
                ),
            )
        }
        None => (
            Vec::new(),
            TokenStream::new(),
            TokenStream::new(),
            zeros,
            TokenStream::new(),
        ),
    };
    let algebraic = fields
        .algebraic
        .iter()
        .map(|&f| Literal::usize_unsuffixed(f));
    let algebraic_fields = (!fields.algebraic.is_empty())
        .then(|| quote!(const ALGEBRAIC_FIELDS: &'static [usize] = &[#(#algebraic),*];));
    // A field model with `#[algebraic]` fields is M·y′ = f, M zero at their cells.
    let dae_items = (!fields.algebraic.is_empty()).then(|| {
        quote! {
            const MASS_MATRIX: bool = true;
            fn mass(&self, state: &#state) -> ::odyn::Result<::odyn::Mass> {
                ::odyn::__private::grid::mass::<Self, #count>(state)
            }
            fn consistent(
                &self,
                t: f64,
                y: &mut #state,
                newton: &::odyn::NewtonOptions,
            ) -> ::odyn::Result<()> {
                ::odyn::__private::grid::consistent::<Self, #count>(self, t, y, newton)
            }
        }
    });
    let model_impl = ModelImpl {
        methods: quote! {
            #dae_items
            fn state(&self) -> #state {
                ::odyn::__private::grid::state(&[#(&self.#grids),*], &[#(#names),*])
            }
            #[inline]
            fn derivative(&self, t: f64, y: &#state, dydt: &mut #state) {
                ::odyn::__private::grid::derivative(self, t, y, dydt)
            }
            fn energy(&self, _: &#state) -> ::core::option::Option<f64> {
                ::core::option::Option::None
            }
        },
        second_order: false,
        jacobian: has_jacobian,
        check: Some(quote! {
            ::odyn::__private::grid::check(self, state)?;
            #(::odyn::__private::grid::check_coefficient::<Self>(#coefficient_names, &self.#coefficients, state)?;)*
            ::core::result::Result::Ok(())
        }),
        ..ModelImpl::for_impl(imp, &fields.item.ident, quote!(#state), args)
    }
    .build();
    quote! {
        #[automatically_derived]
        impl #self_ty {
            #jacobian_fn
        }
        #[automatically_derived]
        impl ::odyn::grid::GridSystem<#count> for #self_ty {
            const FIELDS: [&'static str; #count] = [#(#names),*];
            const BLOCKS: &'static [::odyn::grid::Block] = &[#(#blocks),*];
            #algebraic_fields
            #[inline(always)]
            fn grids(&self) -> [&::odyn::grid::Grid; #count] {
                [#(&self.#grids),*]
            }
            #[inline(always)]
            #[allow(unused_variables)]
            fn cell(
                &self,
                stencils: &[::odyn::grid::Stencil; #count],
                at: ::odyn::grid::Place,
            ) -> [f64; #count] {
                #rate
            }
            #[inline(always)]
            #[allow(unused_variables)]
            fn cell_jacobian(
                &self,
                stencils: &[::odyn::grid::Stencil; #count],
                at: ::odyn::grid::Place,
                blocks: &mut [f64],
            ) {
                #jacobian_call
            }
            #[inline(always)]
            #[allow(unused_variables)]
            fn cell_time_derivative(
                &self,
                stencils: &[::odyn::grid::Stencil; #count],
                at: ::odyn::grid::Place,
            ) -> [f64; #count] {
                #time_call
            }
        }
        #jacobian_impl
        #model_impl
    }
}

fn hidden_name(cell: &Cell) -> syn::Ident {
    format_ident!(
        "__odyn_{}_jacobian",
        cell.f.sig.ident,
        span = Span::mixed_site()
    )
}

fn time_name(cell: &Cell) -> syn::Ident {
    format_ident!(
        "__odyn_{}_time_derivative",
        cell.f.sig.ident,
        span = Span::mixed_site()
    )
}

/// How a kernel's ∂f/∂t is had.
enum Time {
    /// It does not read the time.
    Unread,
    /// Generated: the hidden method of [`time_name`].
    Exact,
    /// The time reaches the rate through code odyn cannot see into.
    Opaque,
}

/// What [`blocks`] generates.
struct Generated {
    /// The structural non-zeros as `odyn::grid::Block`s.
    blocks: Vec<TokenStream>,
    /// The hidden methods: the blocks' values, and ∂f/∂t when [`Time::Exact`].
    function: TokenStream,
    time: Time,
}

/// The structural non-zeros of the kernel's derivative as `odyn::grid::Block`s, a hidden
/// method returning their values at a cell in the same order, and one returning ∂f/∂t of its
/// outputs when it reads the time.
fn blocks(cell: &Cell, lowered: Lowered) -> Generated {
    let Lowered {
        mut graph,
        outputs,
        prologue,
        time,
        exact_time,
    } = lowered;
    let inputs = cell.stencils.len() * NEIGHBOURS.len();
    let pattern = crate::sparsity::pattern(&graph, &outputs, inputs);
    let mut differentiator = Differentiator::default();
    let mut blocks = Vec::new();
    let mut roots = Vec::new();
    for (row, (&output, reads)) in outputs.iter().zip(&pattern).enumerate() {
        for &variable in reads {
            let (stencil, neighbour) = (variable / NEIGHBOURS.len(), variable % NEIGHBOURS.len());
            let column = Literal::usize_unsuffixed(cell.stencils[stencil].1);
            let (row, neighbour) = (
                Literal::usize_unsuffixed(row),
                Literal::usize_unsuffixed(neighbour),
            );
            blocks.push(quote! {
                ::odyn::grid::Block { row: #row, column: #column, neighbour: #neighbour }
            });
            roots.push(differentiator.derivative(&mut graph, output, variable));
        }
    }
    let mut components: Vec<TokenStream> = cell
        .stencils
        .iter()
        .flat_map(|(s, _)| {
            NEIGHBOURS.map(|n| {
                let n = syn::Ident::new(n, Span::call_site());
                quote!(#s.#n)
            })
        })
        .collect();
    let (time_component, time_copy) = time_copy(cell.time.as_ref());
    components.extend(time_component);
    // ∂f/∂t, row by row (0 where a row does not read the time).
    let time_roots: Vec<_> = match time {
        Some(var) if exact_time => outputs
            .iter()
            .map(|&f| differentiator.derivative(&mut graph, f, var))
            .collect(),
        _ => Vec::new(),
    };
    // A hidden method of the kernel's arguments returning the values of `roots`.
    let values_fn = |name: syn::Ident, roots: &[crate::ir::ExprId]| {
        let (prologue, lets) = evaluation(&graph, roots, &components, &prologue);
        let values = roots.iter().map(|&id| operand(&graph, id, &components));
        let count = Literal::usize_unsuffixed(roots.len());
        let inputs = &cell.f.sig.inputs;
        hidden_fn(
            quote!(#name(#inputs) -> [f64; #count]),
            quote!(#[inline(always)]),
            &time_copy,
            &prologue,
            quote!(#(#lets)* [#(#values),*]),
        )
    };
    let mut function = values_fn(hidden_name(cell), &roots);
    let time = match time {
        None => Time::Unread,
        Some(_) if !exact_time => Time::Opaque,
        Some(_) => {
            function.extend(values_fn(time_name(cell), &time_roots));
            Time::Exact
        }
    };
    Generated {
        blocks,
        function,
        time,
    }
}
