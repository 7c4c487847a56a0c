//! The Jacobian of a fixed-size model as generated code: one expression per structural
//! non-zero up to `SYMBOLIC_LIMIT`, coloured forward mode ([`super::tangent`]) above; stored
//! in an `SMatrix` up to `SMALL` components and a `FaerDense` above; and ∂f/∂t.

use proc_macro2::{Span, TokenStream};
use quote::{format_ident, quote};
use syn::ItemImpl;

use super::functions::Function;
use super::layout::{
    JacobianBody, SMALL, component_tokens, inline_hint, state_args, state_params, time_param,
};
use crate::generate::{
    evaluation, hidden_fn, opaques_read, operand, prologue_tokens, straight_line, time_copy,
    time_independent,
};
use crate::ir::ExprId;
use crate::lower::{Lowered, Prologue};
use crate::model::Model;

/// Bigger models with at most this many structural non-zeros get one expression per entry; more
/// than that, and the Jacobian comes from coloured forward mode (see [`crate::sparsity`]): a
/// banded 1000-component model stays symbolic, a dense 65-component one does not.
const SYMBOLIC_LIMIT: usize = 4096;

/// The `Jacobian` impl: the derivatives of the lowered force, emitted as straight-line code.
pub(crate) fn jacobian(
    model: &Model<'_>,
    lowered: Lowered,
    force: &Function,
    imp: &ItemImpl,
) -> TokenStream {
    let self_ty = &imp.self_ty;
    let state = model.state_ident();
    let n = proc_macro2::Literal::usize_unsuffixed(model.len());
    let Lowered {
        mut graph,
        outputs,
        prologue,
        time: time_var,
        exact_time,
    } = lowered;
    let mut differentiator = crate::derivative::Differentiator::default();
    let mut components = component_tokens(model);
    let (time_component, time_copy) = time_copy(time_ident(force));
    components.extend(time_component);
    let jac = format_ident!("__odyn_jac", span = Span::mixed_site());
    let n_usize = model.len();
    let (matrix, body) = if n_usize <= SMALL {
        let entries = symbolic_entries(&mut graph, &mut differentiator, &outputs, |_| 0..n_usize);
        (
            quote!(::odyn::__private::nalgebra::SMatrix<f64, #n, #n>),
            small_store(&graph, &entries, n_usize, &components, &jac),
        )
    } else {
        let rows = crate::sparsity::pattern(&graph, &outputs, n_usize);
        let count: usize = rows.iter().map(Vec::len).sum();
        let body = if count <= SYMBOLIC_LIMIT {
            let entries = symbolic_entries(&mut graph, &mut differentiator, &outputs, |row| {
                rows[row].iter().copied()
            });
            listed_store(&graph, &entries, &components, &jac)
        } else {
            let mut extended = components.clone();
            super::tangent::jacobian(
                &mut graph,
                &mut differentiator,
                &outputs,
                rows,
                &mut extended,
                &jac,
            )
        };
        (quote!(::odyn::FaerDense), body)
    };
    let JacobianBody {
        statements: body,
        nonzeros,
        reads,
    } = body;
    // ∂f/∂t: the time is one more variable of the graph.
    let mut time_entries: Vec<(usize, ExprId)> = Vec::new();
    if let Some(var) = time_var {
        for (row, &f) in outputs.iter().enumerate() {
            let d = differentiator.derivative(&mut graph, f, var);
            if !graph.is_zero(d) {
                time_entries.push((row, d));
            }
        }
    }
    let count = nonzeros.len();
    let nonzeros = nonzeros.iter().map(|&(r, c)| quote!((#r, #c)));
    let (time_derivative, time_derivative_impl) = time_derivative(
        model,
        &graph,
        &time_entries,
        exact_time,
        &components,
        &prologue,
        force,
    );
    let prologue = prologue_tokens(&prologue, &opaques_read(&graph, &reads));
    let receiver = &force.receiver;
    let time = time_param(force);
    let params = state_params(model);
    let jacobian_fn = hidden_fn(
        quote!(__odyn_jacobian(#receiver, #time, #(#params,)* #jac: &mut #matrix)),
        inline_hint(model, quote!(#[inline])),
        &time_copy,
        &prologue,
        body,
    );
    let y = format_ident!("y");
    let args = state_args(model, &y);
    let doc = format!(
        "The {count} structural non-zeros of ∂f/∂y, derived by `#[system]` from the model's code."
    );
    let zeros = zero_matrix(n_usize, &quote!(#n));
    let exact = if graph.has_externs() {
        quote! {
            /// False: the model calls a function `#[system]` cannot see inside; the derivative
            /// of each such call is a central difference of the call.
            const EXACT: bool = false;
        }
    } else {
        TokenStream::new()
    };
    quote! {
        #[automatically_derived]
        impl #self_ty {
            #jacobian_fn
            #time_derivative
        }
        #[automatically_derived]
        impl ::odyn::Jacobian for #self_ty {
            type Matrix = #matrix;
            #[doc = #doc]
            const NONZEROS: &'static [(usize, usize)] = &[#(#nonzeros),*];
            #exact
            #[inline]
            fn jacobian_matrix(&self, _: &#state) -> #matrix {
                #zeros
            }
            #[inline]
            fn jacobian(&self, t: f64, y: &#state, jacobian: &mut #matrix) {
                self.__odyn_jacobian(t, #(#args,)* jacobian)
            }
            #time_derivative_impl
        }
    }
}

/// The `Jacobian` impl of a model that asked for `jacobian = finite_differences`: central
/// differences of its own f ([`odyn::__private::central_differences`]), every entry, and ∂f/∂t
/// by the runtime's central difference when f reads the time.
pub(crate) fn differences(model: &Model<'_>, force: &Function, imp: &ItemImpl) -> TokenStream {
    let self_ty = &imp.self_ty;
    let (impl_generics, _, where_clause) = imp.generics.split_for_impl();
    let state = model.state_type();
    let (matrix, store, state_param, zeros) = if !model.is_generic() && model.len() <= SMALL {
        let n = model.len_tokens();
        (
            quote!(::odyn::__private::nalgebra::SMatrix<f64, #n, #n>),
            quote!(|row, column, value| jacobian[(row, column)] = value),
            quote!(_),
            zero_matrix(model.len(), &n),
        )
    } else {
        (
            quote!(::odyn::FaerDense),
            quote!(|row, column, value| jacobian.set(row, column, value)),
            // A const-generic model's size is known once the state is.
            quote!(state),
            quote!(::odyn::FaerDense::zeros(
                ::odyn::State::as_slice(state).len()
            )),
        )
    };
    let time = match force.time {
        Some(_) => quote!(
            const TIME_DEPENDENT: bool = true;
        ),
        None => time_independent(&state, "The model's function does not read the time"),
    };
    let why = if model.is_generic() {
        " False: a const-generic model's Jacobian is central differences of f."
    } else {
        " False: `jacobian = finite_differences`, central differences of f."
    };
    quote! {
        #[automatically_derived]
        impl #impl_generics ::odyn::Jacobian for #self_ty #where_clause {
            type Matrix = #matrix;
            /// Not known: the Jacobian is taken by finite differences.
            const NONZEROS: &'static [(usize, usize)] = &[];
            #[doc = #why]
            const EXACT: bool = false;
            #[inline]
            fn jacobian_matrix(&self, #state_param: &#state) -> #matrix {
                #zeros
            }
            #[inline]
            fn jacobian(&self, t: f64, y: &#state, jacobian: &mut #matrix) {
                ::odyn::__private::central_differences(self, t, y, #store)
            }
            #time
        }
    }
}

/// A new n×n Jacobian (`n` also as tokens): an `SMatrix` on the stack up to [`SMALL`], a
/// `FaerDense` above.
fn zero_matrix(n: usize, tokens: &TokenStream) -> TokenStream {
    if n <= SMALL {
        quote!(::odyn::__private::nalgebra::SMatrix::<f64, #tokens, #tokens>::zeros())
    } else {
        quote!(::odyn::FaerDense::zeros(#tokens))
    }
}

/// The derivative of each output by each of its `columns`, the structural zeros dropped.
fn symbolic_entries<C: IntoIterator<Item = usize>>(
    graph: &mut crate::ir::Graph,
    differentiator: &mut crate::derivative::Differentiator,
    outputs: &[ExprId],
    columns: impl Fn(usize) -> C,
) -> Vec<(usize, usize, ExprId)> {
    let mut entries = Vec::new();
    for (row, &f) in outputs.iter().enumerate() {
        for column in columns(row) {
            let d = differentiator.derivative(graph, f, column);
            if !graph.is_zero(d) {
                entries.push((row, column, d));
            }
        }
    }
    entries
}

/// The Jacobian body of a model small enough for a stack matrix: one expression per structural
/// non-zero, the whole matrix stored in one expression column by column with structural zeros as
/// literals, so the optimiser keeps it in registers as it would a hand-written `Matrix3::new(..)`.
fn small_store(
    graph: &crate::ir::Graph,
    entries: &[(usize, usize, ExprId)],
    n: usize,
    components: &[TokenStream],
    jac: &syn::Ident,
) -> JacobianBody {
    let roots: Vec<ExprId> = entries.iter().map(|e| e.2).collect();
    let lets = straight_line(graph, &roots, components);
    let columns = (0..n).map(|c| {
        let rows = (0..n).map(|r| match entries.iter().find(|e| e.0 == r && e.1 == c) {
            Some(&(_, _, d)) => operand(graph, d, components),
            None => quote!(0.0f64),
        });
        quote!([#(#rows),*])
    });
    JacobianBody {
        statements: quote! {
            #(#lets)*
            *#jac = ::odyn::__private::nalgebra::SMatrix::from_array_storage(
                ::odyn::__private::nalgebra::ArrayStorage([#(#columns),*]),
            );
        },
        nonzeros: entries.iter().map(|&(r, c, _)| (r, c)).collect(),
        reads: roots,
    }
}

/// The Jacobian body of a bigger model with few non-zeros: one expression per entry, the values
/// in one array stored by one loop over `NONZEROS` (a `set` call per entry costs the compiler
/// more than the entry's arithmetic).
fn listed_store(
    graph: &crate::ir::Graph,
    entries: &[(usize, usize, ExprId)],
    components: &[TokenStream],
    jac: &syn::Ident,
) -> JacobianBody {
    let roots: Vec<ExprId> = entries.iter().map(|e| e.2).collect();
    let lets = straight_line(graph, &roots, components);
    let values = entries
        .iter()
        .map(|&(_, _, d)| operand(graph, d, components));
    let count = entries.len();
    JacobianBody {
        statements: quote! {
            #(#lets)*
            let __odyn_values: [f64; #count] = [#(#values),*];
            #jac.fill_zero();
            for (&(i, j), &value) in <Self as ::odyn::Jacobian>::NONZEROS.iter().zip(&__odyn_values) {
                #jac.set(i, j, value);
            }
        },
        nonzeros: entries.iter().map(|&(r, c, _)| (r, c)).collect(),
        reads: roots,
    }
}

/// The name of the force's time argument, if it has one.
pub(super) fn time_ident(force: &Function) -> Option<&syn::Ident> {
    force.time.as_ref().and_then(|t| match &*t.pat {
        syn::Pat::Ident(p) => Some(&p.ident),
        _ => None,
    })
}

/// The hidden ∂f/∂t function and the `Jacobian` items that use it: exact straight-line code when
/// every path from the time to f went through supported operations; a compile-time zero (and
/// `TIME_DEPENDENT = false`) when f does not read the time; otherwise the runtime's default, a
/// central difference (the time reached f through the user's own function of `t`).
fn time_derivative(
    model: &Model<'_>,
    graph: &crate::ir::Graph,
    entries: &[(usize, ExprId)],
    exact: bool,
    components: &[TokenStream],
    prologue: &[Prologue],
    force: &Function,
) -> (Option<TokenStream>, TokenStream) {
    let (_, time_copy) = time_copy(time_ident(force));
    let state = model.state_ident();
    let y = format_ident!("y");
    let args: Vec<_> = state_args(model, &y).collect();
    if !exact {
        return (
            None,
            quote!(
                const TIME_DEPENDENT: bool = true;
            ),
        );
    }
    if entries.is_empty() {
        return (
            None,
            time_independent(&state, "The model's function does not read the time"),
        );
    }
    let roots: Vec<ExprId> = entries.iter().map(|e| e.1).collect();
    let (prologue, lets) = evaluation(graph, &roots, components, prologue);
    let stores = entries.iter().map(|&(row, d)| {
        let value = operand(graph, d, components);
        quote!(out[#row] = #value;)
    });
    let receiver = &force.receiver;
    let time = time_param(force);
    let params = state_params(model);
    let out = format_ident!("__odyn_dfdt", span = Span::mixed_site());
    let hidden = hidden_fn(
        quote!(__odyn_time_derivative(#receiver, #time, #(#params,)* #out: &mut #state)),
        inline_hint(model, quote!(#[inline])),
        &time_copy,
        &prologue,
        quote! {
            #(#lets)*
            let out = ::odyn::State::as_mut_slice(#out);
            out.fill(0.0);
            #(#stores)*
        },
    );
    (
        Some(hidden),
        quote! {
            const TIME_DEPENDENT: bool = true;
            #[inline]
            fn time_derivative(&self, t: f64, y: &#state, dfdt: &mut #state) {
                self.__odyn_time_derivative(t, #(#args,)* dfdt)
            }
        },
    )
}
