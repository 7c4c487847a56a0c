//! The expression graph as straight-line Rust: one `let` per operation node, operands by name.
//! The prologue that runs before it is [`super::prologue`]'s.
//!
//! Every `let` opens a lexical scope nested in the previous one's, and with debuginfo LLVM walks
//! that tree of scopes recursively: about 2500 `let`s in a row in one function overflowed
//! rustc's stack in a dev build (rustc 1.95, measured; a 3000-term force or a 32 × 32 stencil
//! has more). So no run is longer than [`RUN`]: a longer straight line goes in blocks of at most
//! [`RUN`] `let`s, each handing on, by an array pattern, the values read after it, and a long
//! run of opaque values is bound [`RUN`] at a time. The values and the order of the operations
//! do not change, only the scopes; code of at most [`RUN`] values reads as before.

use std::collections::HashSet;

use proc_macro2::{Span, TokenStream};
use quote::{ToTokens, format_ident, quote};

use crate::ir::{ExprId, Node};

/// Most `let`s generated in a row in one block (see the module docs). Blocks nest at most two
/// deep below 256² values, so a function's scopes stay within a few hundred levels.
pub(crate) const RUN: usize = 256;

/// How a graph node is read in generated code: a literal, a state component, an opaque value or
/// the `let` of an earlier node.
pub(crate) fn operand(
    graph: &crate::ir::Graph,
    id: ExprId,
    components: &[TokenStream],
) -> TokenStream {
    match graph.node(id) {
        Node::Const(bits) => float_literal(f64::from_bits(bits)),
        Node::Var(k) => components[k].clone(),
        Node::Opaque(i) => opaque_ident(i).into_token_stream(),
        _ => node_ident(id).into_token_stream(),
    }
}

/// One `let` per operation node that `roots` need, in dependency order: straight-line code.
pub(crate) fn straight_line(
    graph: &crate::ir::Graph,
    roots: &[ExprId],
    components: &[TokenStream],
) -> Vec<TokenStream> {
    lets(
        graph,
        &graph.reachable(roots.iter().copied()),
        components,
        roots,
    )
}

/// One `let` per operation node of `ids` (in arena order, so dependencies come first), in blocks
/// of at most [`RUN`]; `read_after` are the nodes the code after these statements reads, which
/// must stay in scope.
pub(crate) fn lets(
    graph: &crate::ir::Graph,
    ids: &[ExprId],
    components: &[TokenStream],
    read_after: &[ExprId],
) -> Vec<TokenStream> {
    lets_in_runs(graph, ids, components, read_after, RUN)
}

/// [`lets`], in runs of at most `run`.
fn lets_in_runs(
    graph: &crate::ir::Graph,
    ids: &[ExprId],
    components: &[TokenStream],
    read_after: &[ExprId],
    run: usize,
) -> Vec<TokenStream> {
    let operations: Vec<ExprId> = ids
        .iter()
        .copied()
        .filter(|&id| {
            !matches!(
                graph.node(id),
                Node::Const(_) | Node::Var(_) | Node::Opaque(_)
            )
        })
        .collect();
    let live = read_after.iter().copied().collect();
    blocks(graph, &operations, components, &live, run)
}

/// The `let`s of `operations`: a run of at most `run` of them, or at most `run` blocks (each
/// again split if longer than `run`), so `let`s nest at most `run` deep per level of blocks;
/// `live` are the nodes read after them.
fn blocks(
    graph: &crate::ir::Graph,
    operations: &[ExprId],
    components: &[TokenStream],
    live: &HashSet<ExprId>,
    run: usize,
) -> Vec<TokenStream> {
    if operations.len() <= run {
        return operations
            .iter()
            .filter_map(|&id| binding(graph, id, components))
            .collect();
    }
    let size = run.max(operations.len().div_ceil(run));
    let mut live = live.clone();
    let mut statements = Vec::new();
    // Backwards, so `live` holds what the blocks after this one read.
    for block in operations.chunks(size).rev() {
        let handed_on: Vec<ExprId> = block
            .iter()
            .copied()
            .filter(|id| live.contains(id))
            .collect();
        for &id in block {
            live.extend(graph.node(id).children());
        }
        if handed_on.is_empty() {
            continue;
        }
        let inner = blocks(
            graph,
            block,
            components,
            &handed_on.iter().copied().collect(),
            run,
        );
        let names: Vec<syn::Ident> = handed_on.iter().map(|&id| node_ident(id)).collect();
        statements.push(match names.as_slice() {
            [name] => quote!(let #name: f64 = { #(#inner)* #name };),
            names => {
                let count = names.len();
                quote!(let [#(#names),*]: [f64; #count] = { #(#inner)* [#(#names),*] };)
            }
        });
    }
    statements.reverse();
    statements
}

/// `let __odyn_e<id>: f64 = <the operation of node id>;`, or nothing for a leaf (a constant, a
/// variable, an opaque value), which is read in place.
fn binding(
    graph: &crate::ir::Graph,
    id: ExprId,
    components: &[TokenStream],
) -> Option<TokenStream> {
    let operand = |id| operand(graph, id, components);
    let value = match graph.node(id) {
        Node::Const(_) | Node::Var(_) | Node::Opaque(_) => return None,
        Node::Add(a, b) => {
            let (a, b) = (operand(a), operand(b));
            quote!(#a + #b)
        }
        Node::Mul(a, b) => {
            let (a, b) = (operand(a), operand(b));
            quote!(#a * #b)
        }
        Node::Div(a, b) => {
            let (a, b) = (operand(a), operand(b));
            quote!(#a / #b)
        }
        Node::Neg(a) => {
            let a = operand(a);
            quote!(-#a)
        }
        Node::Powi(a, k) => {
            let a = operand(a);
            quote!(#a.powi(#k))
        }
        Node::Powf(a, b) => {
            let (a, b) = (operand(a), operand(b));
            crate::math::call(&format_ident!("powf"), a, &[b])
        }
        Node::Call(f, a) => {
            let a = operand(a);
            let method = format_ident!("{}", f.method());
            if crate::math::routed(f.method(), 0) {
                crate::math::call(&method, a, &[])
            } else {
                quote!(#a.#method())
            }
        }
        Node::Call2(f, a, b) => {
            let (a, b) = (operand(a), operand(b));
            let method = format_ident!("{}", f.method());
            if crate::math::routed(f.method(), 1) {
                crate::math::call(&method, a, &[b])
            } else {
                quote!(#a.#method(#b))
            }
        }
        Node::Select {
            selector,
            arm,
            then,
            otherwise,
        } => {
            let (then, otherwise) = (operand(then), operand(otherwise));
            let selector = selector_ident(selector);
            let arm = arm as usize;
            quote!(if #selector == #arm { #then } else { #otherwise })
        }
        Node::Pick {
            a,
            b,
            then,
            otherwise,
        } => {
            let (a, b) = (operand(a), operand(b));
            let (then, otherwise) = (operand(then), operand(otherwise));
            quote!(if #a <= #b { #then } else { #otherwise })
        }
        Node::Extern {
            function,
            args,
            arity,
        } => {
            let path = graph.extern_path(function);
            let args = args[..usize::from(arity)].iter().map(|&a| operand(a));
            quote!(#path(#(#args),*))
        }
        Node::Slope {
            function,
            args,
            arity,
            wrt,
        } => {
            let path = graph.extern_path(function);
            let wrt = usize::from(wrt);
            let at = operand(args[wrt]);
            // ε^⅓ (the step that balances a central difference's truncation and rounding).
            let step = float_literal(libm::cbrt(f64::EPSILON));
            let shifted = |shift: TokenStream| {
                let args = args[..usize::from(arity)]
                    .iter()
                    .enumerate()
                    .map(|(i, &a)| if i == wrt { shift.clone() } else { operand(a) });
                quote!(#path(#(#args),*))
            };
            let up = format_ident!("__odyn_up", span = Span::mixed_site());
            let down = format_ident!("__odyn_down", span = Span::mixed_site());
            let (plus, minus) = (
                shifted(up.to_token_stream()),
                shifted(down.to_token_stream()),
            );
            quote!({
                let __odyn_h: f64 = #step * f64::max(f64::abs(#at), 1.0);
                let #up: f64 = #at + __odyn_h;
                let #down: f64 = #at - __odyn_h;
                (#plus - #minus) / (#up - #down)
            })
        }
    };
    let name = node_ident(id);
    Some(quote!(let #name: f64 = #value;))
}

pub(super) fn selector_ident(index: u32) -> syn::Ident {
    format_ident!("__odyn_s{}", index, span = Span::mixed_site())
}

fn node_ident(id: ExprId) -> syn::Ident {
    format_ident!("__odyn_e{}", id.index(), span = Span::mixed_site())
}

pub(super) fn opaque_ident(index: usize) -> syn::Ident {
    format_ident!("__odyn_p{}", index, span = Span::mixed_site())
}

fn float_literal(value: f64) -> TokenStream {
    if value.is_finite() {
        let literal = proc_macro2::Literal::f64_suffixed(value);
        quote!((#literal))
    } else if value.is_nan() {
        quote!(f64::NAN)
    } else if value > 0.0 {
        quote!(f64::INFINITY)
    } else {
        quote!(f64::NEG_INFINITY)
    }
}

#[cfg(test)]
pub(super) mod tests;
