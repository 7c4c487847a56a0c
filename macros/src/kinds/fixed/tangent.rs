//! Stage 6, big models: the Jacobian by coloured forward mode instead of one expression per
//! entry (see [`crate::sparsity`] for why and for the colouring).
//!
//! The emitted body evaluates the force's values once, then for each column group sets the seed
//! vector to 1 on the group's columns, evaluates the tangent of every output — the Jacobian's
//! columns of that group summed, each row holding the one entry the group has in it — and
//! scatters it into the matrix. The structural non-zeros are listed group by group, so the
//! `NONZEROS` constant doubles as the scatter table.

use proc_macro2::{Span, TokenStream};
use quote::{format_ident, quote};

use super::layout::JacobianBody;
use crate::derivative::Differentiator;
use crate::generate::{lets, operand};
use crate::ir::{ExprId, Graph, Node};
use crate::sparsity::column_groups;

/// Emits the forward-mode Jacobian of `outputs`, whose dependencies on the state are `rows`
/// ([`crate::sparsity::pattern`]). `components` names each graph variable in generated code (the
/// state's, then the time if f reads it); it is extended with the seed vector's components.
pub(crate) fn jacobian(
    graph: &mut Graph,
    differentiator: &mut Differentiator,
    outputs: &[ExprId],
    rows: Vec<Vec<usize>>,
    components: &mut Vec<TokenStream>,
    jacobian: &syn::Ident,
) -> JacobianBody {
    let n = outputs.len();
    let groups = column_groups(&rows, n);
    let mut columns: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, row) in rows.iter().enumerate() {
        for &j in row {
            columns[j].push(i);
        }
    }
    let mut nonzeros = Vec::new();
    let mut starts = vec![0usize];
    for group in &groups {
        nonzeros.extend(
            group
                .iter()
                .flat_map(|&j| columns[j].iter().map(move |&i| (i, j))),
        );
        starts.push(nonzeros.len());
    }

    // Variables 0..n are the state, n the time; the seeds follow.
    let first_seed = n + 1;
    components.resize(first_seed, quote!(0.0f64));
    let seed = format_ident!("__odyn_seed", span = Span::mixed_site());
    components.extend((0..n).map(|k| quote!(#seed[#k])));
    let tangents: Vec<ExprId> = outputs
        .iter()
        .map(|&f| differentiator.tangent(graph, f, first_seed, n))
        .collect();

    // Values that do not depend on the seed are computed once, before the loop over groups.
    let order = graph.reachable(tangents.iter().copied());
    let mut seeded = vec![false; order.last().map_or(0, |id| id.index() + 1)];
    for &id in &order {
        seeded[id.index()] = match graph.node(id) {
            Node::Var(k) => k >= first_seed,
            node => node.children().any(|c| seeded[c.index()]),
        };
    }
    let (inside, outside): (Vec<ExprId>, Vec<ExprId>) =
        order.into_iter().partition(|id| seeded[id.index()]);
    // What the loop reads of the values before it: its own operands, and tangents that do not
    // depend on the seed.
    let read_in_loop: Vec<ExprId> = inside
        .iter()
        .flat_map(|&id| graph.node(id).children())
        .chain(tangents.iter().copied())
        .collect();
    let before = lets(graph, &outside, components, &read_in_loop);
    let each = lets(graph, &inside, components, &tangents);
    let values = tangents.iter().map(|&d| operand(graph, d, components));

    let count = groups.len();
    let n_lit = proc_macro2::Literal::usize_unsuffixed(n);
    let group = format_ident!("__odyn_group", span = Span::mixed_site());
    let entries = format_ident!("__odyn_entries", span = Span::mixed_site());
    let tangent = format_ident!("__odyn_tangent", span = Span::mixed_site());
    let statements = quote! {
        #(#before)*
        const GROUP_STARTS: [usize; #count + 1] = [#(#starts),*];
        #jacobian.fill_zero();
        let mut #seed = [0.0f64; #n_lit];
        for #group in 0..#count {
            let #entries = &<Self as ::odyn::Jacobian>::NONZEROS
                [GROUP_STARTS[#group]..GROUP_STARTS[#group + 1]];
            for &(_, j) in #entries {
                #seed[j] = 1.0;
            }
            #(#each)*
            let #tangent: [f64; #n_lit] = [#(#values),*];
            for &(i, j) in #entries {
                #jacobian.set(i, j, #tangent[i]);
                #seed[j] = 0.0;
            }
        }
    };
    JacobianBody {
        statements,
        nonzeros,
        reads: tangents,
    }
}
