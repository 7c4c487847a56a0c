//! The expression graph as straight-line Rust: one `let` per operation node, operands by name,
//! and the prologue (the user's state-free statements, opaque values and branches on
//! parameters) that runs before it.

use proc_macro2::{Span, TokenStream};
use quote::{ToTokens, format_ident, quote};

use crate::ir::{ExprId, Node};
use crate::lower::{Branch, BranchKind, Prologue};

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
    lets(graph, &graph.reachable(roots.iter().copied()), components)
}

/// One `let` per operation node of `ids` (in arena order, so dependencies come first).
pub(crate) fn lets(
    graph: &crate::ir::Graph,
    ids: &[ExprId],
    components: &[TokenStream],
) -> Vec<TokenStream> {
    let operand = |id| operand(graph, id, components);
    ids.iter()
        .filter_map(|&id| {
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
                    quote!(#a.powf(#b))
                }
                Node::Call(f, a) => {
                    let a = operand(a);
                    let method = format_ident!("{}", f.method());
                    quote!(#a.#method())
                }
                Node::Call2(f, a, b) => {
                    let (a, b) = (operand(a), operand(b));
                    let method = format_ident!("{}", f.method());
                    quote!(#a.#method(#b))
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
            };
            let name = node_ident(id);
            Some(quote!(let #name: f64 = #value;))
        })
        .collect()
}

/// The prologue as statements: the user's state-independent code, the opaque values, and the
/// branches on parameters, each setting its selector to the arm it took. Opaque values and
/// selectors set inside a branch are declared before it (NaN and `usize::MAX` until an arm sets
/// them), since the straight-line code that follows reads every arm's values.
pub(crate) fn prologue_tokens(prologue: &[Prologue]) -> Vec<TokenStream> {
    let mut declared = Vec::new();
    for item in prologue {
        if let Prologue::Branch(branch) = item {
            declare(branch, &mut declared);
        }
    }
    declared.extend(prologue.iter().map(|p| prologue_item(p, true)));
    declared
}

fn declare(branch: &Branch, out: &mut Vec<TokenStream>) {
    let selector = selector_ident(branch.selector);
    out.push(quote!(let mut #selector: usize = usize::MAX;));
    for item in branch.arms.iter().flatten() {
        match item {
            Prologue::Opaque(i, _) => {
                let name = opaque_ident(*i);
                out.push(quote!(let mut #name: f64 = f64::NAN;));
            }
            Prologue::Branch(inner) => declare(inner, out),
            Prologue::Stmt(_) => {}
        }
    }
}

fn prologue_item(item: &Prologue, top: bool) -> TokenStream {
    match item {
        Prologue::Stmt(stmt) => stmt.to_token_stream(),
        Prologue::Opaque(i, tokens) => {
            let name = opaque_ident(*i);
            if top {
                quote!(let #name: f64 = #tokens;)
            } else {
                quote!(#name = #tokens;)
            }
        }
        Prologue::Branch(branch) => {
            let selector = selector_ident(branch.selector);
            let arms: Vec<TokenStream> = branch
                .arms
                .iter()
                .enumerate()
                .map(|(k, arm)| {
                    let items = arm.iter().map(|p| prologue_item(p, false));
                    quote!({ #(#items)* #selector = #k; })
                })
                .collect();
            match &branch.kind {
                BranchKind::If(conditions) => {
                    let mut tokens = TokenStream::new();
                    for (k, (condition, arm)) in conditions.iter().zip(&arms).enumerate() {
                        let keyword = if k == 0 { quote!(if) } else { quote!(else if) };
                        tokens.extend(quote!(#keyword #condition #arm));
                    }
                    let last = &arms[arms.len() - 1];
                    tokens.extend(quote!(else #last));
                    tokens
                }
                BranchKind::Match(scrutinee, patterns) => {
                    let cases = patterns.iter().zip(&arms).map(|((pat, guard), arm)| {
                        let guard = guard.as_ref().map(|g| quote!(if #g));
                        quote!(#pat #guard => #arm)
                    });
                    quote!(match #scrutinee { #(#cases)* })
                }
            }
        }
    }
}

fn selector_ident(index: u32) -> syn::Ident {
    format_ident!("__odyn_s{}", index, span = Span::mixed_site())
}

fn node_ident(id: ExprId) -> syn::Ident {
    format_ident!("__odyn_e{}", id.index(), span = Span::mixed_site())
}

fn opaque_ident(index: usize) -> syn::Ident {
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
