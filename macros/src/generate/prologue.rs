//! The prologue as statements: what runs before the straight-line code ([`super::code`]) — the
//! user's state-free statements, the opaque values the code reads, and the branches on
//! parameters, each recording the arm it took. Bound [`RUN`] to a `let` where long, for the
//! reason [`super::code`]'s module docs give.

use std::collections::HashSet;

use proc_macro2::TokenStream;
use quote::{ToTokens, quote};

use super::code::{RUN, opaque_ident, selector_ident};
use crate::ir::{ExprId, Node};
use crate::lower::{Branch, BranchKind, Prologue};

/// The opaque values that the nodes `roots` need read: the prologue computes only these (a
/// state-free local the graph never reads, such as `let n = self.count;` of a `usize`, is not an
/// `f64` to compute).
pub(crate) fn opaques_read(graph: &crate::ir::Graph, roots: &[ExprId]) -> HashSet<usize> {
    graph
        .reachable(roots.iter().copied())
        .into_iter()
        .filter_map(|id| match graph.node(id) {
            Node::Opaque(i) => Some(i),
            _ => None,
        })
        .collect()
}

/// The prologue as statements: the user's state-independent code, the opaque values of `read`
/// ([`opaques_read`]), the branches on parameters, each setting its selector to the arm it
/// took, and the blocks of inlined helpers. Opaque values and selectors set inside a branch (or a
/// helper's block) are declared before it (NaN and
/// `usize::MAX` until an arm sets them), since the straight-line code that follows reads every
/// arm's values. Past [`RUN`] declarations, or [`RUN`] opaque values at the top, they are bound
/// [`RUN`] to a `let` (see the module docs).
pub(crate) fn prologue_tokens(prologue: &[Prologue], read: &HashSet<usize>) -> Vec<TokenStream> {
    let mut selectors = Vec::new();
    let mut values = Vec::new();
    let mut statements = Vec::new();
    for item in prologue {
        match item {
            Prologue::Branch(branch) => {
                declare(branch, read, &mut selectors, &mut values, &mut statements);
            }
            Prologue::Scope(items) => {
                declare_items(items, read, &mut selectors, &mut values, &mut statements);
            }
            Prologue::Stmt(_) | Prologue::Opaque(..) => {}
        }
    }
    if selectors.len() + values.len() > RUN {
        statements = declared(&selectors, quote!(usize), quote!(usize::MAX));
        statements.extend(declared(&values, quote!(f64), quote!(f64::NAN)));
    }
    let opaques = prologue
        .iter()
        .filter(|p| matches!(p, Prologue::Opaque(i, _) if read.contains(i)))
        .count();
    let mut run: Vec<(syn::Ident, &TokenStream)> = Vec::new();
    for item in prologue {
        match item {
            Prologue::Opaque(i, _) if !read.contains(i) => {}
            Prologue::Opaque(i, tokens) if opaques > RUN => run.push((opaque_ident(*i), tokens)),
            _ => {
                statements.extend(opaque_run(&std::mem::take(&mut run)));
                statements.push(prologue_item(item, read, true));
            }
        }
    }
    statements.extend(opaque_run(&run));
    statements
        .into_iter()
        .map(crate::math::route_statements)
        .map(f64_zeros)
        .collect()
}

/// `Vector2::zeros()` → `Vector2::<f64>::zeros()` in the prologue's copies of the user's
/// state-free code: there the later uses that fix the number type (state-dependent, so not
/// copied) are missing, and rustc could not infer it.
fn f64_zeros(tokens: TokenStream) -> TokenStream {
    use syn::visit_mut::{self, VisitMut};
    struct Zeros;
    impl VisitMut for Zeros {
        fn visit_expr_path_mut(&mut self, e: &mut syn::ExprPath) {
            visit_mut::visit_expr_path_mut(self, e);
            let segments = &mut e.path.segments;
            let n = segments.len();
            if n >= 2
                && segments[n - 1].ident == "zeros"
                && segments[n - 2]
                    .ident
                    .to_string()
                    .strip_prefix("Vector")
                    .and_then(|k| k.parse::<usize>().ok())
                    .is_some_and(|k| (1..=6).contains(&k))
                && segments[n - 2].arguments.is_none()
            {
                segments[n - 2].arguments =
                    syn::PathArguments::AngleBracketed(syn::parse_quote!(::<f64>));
            }
        }
    }
    match syn::parse2::<syn::Block>(quote::quote!({ #tokens })) {
        Ok(mut block) => {
            Zeros.visit_block_mut(&mut block);
            let statements = block.stmts;
            quote::quote!(#(#statements)*)
        }
        Err(_) => tokens,
    }
}

/// Collects the selectors and the opaque values (of those `read`) set inside `branch`, and their
/// declarations one `let` each.
fn declare(
    branch: &Branch,
    read: &HashSet<usize>,
    selectors: &mut Vec<syn::Ident>,
    values: &mut Vec<syn::Ident>,
    out: &mut Vec<TokenStream>,
) {
    if !matches!(branch.kind, BranchKind::Every) {
        let selector = selector_ident(branch.selector);
        out.push(quote!(let mut #selector: usize = usize::MAX;));
        selectors.push(selector);
    }
    for arm in &branch.arms {
        declare_items(arm, read, selectors, values, out);
    }
}

/// [`declare`] for the items of a block (a branch's arm, an inlined helper's scope).
fn declare_items(
    items: &[Prologue],
    read: &HashSet<usize>,
    selectors: &mut Vec<syn::Ident>,
    values: &mut Vec<syn::Ident>,
    out: &mut Vec<TokenStream>,
) {
    for item in items {
        match item {
            Prologue::Opaque(i, _) if read.contains(i) => {
                let name = opaque_ident(*i);
                out.push(quote!(let mut #name: f64 = f64::NAN;));
                values.push(name);
            }
            Prologue::Opaque(..) => {}
            Prologue::Branch(inner) => declare(inner, read, selectors, values, out),
            Prologue::Scope(inner) => declare_items(inner, read, selectors, values, out),
            Prologue::Stmt(_) => {}
        }
    }
}

/// `names` declared [`RUN`] to a `let`: `let [mut a, mut b, …]: [ty; n] = [initial; n];`.
fn declared(names: &[syn::Ident], ty: TokenStream, initial: TokenStream) -> Vec<TokenStream> {
    names
        .chunks(RUN)
        .map(|chunk| {
            let count = chunk.len();
            quote!(let [#(mut #chunk),*]: [#ty; #count] = [#initial; #count];)
        })
        .collect()
}

/// A run of opaque values at the top of the prologue, [`RUN`] to a `let`:
/// `let [p0, p1, …]: [f64; n] = [<value 0>, <value 1>, …];`.
fn opaque_run(run: &[(syn::Ident, &TokenStream)]) -> Vec<TokenStream> {
    run.chunks(RUN)
        .map(|chunk| {
            let names = chunk.iter().map(|(name, _)| name);
            let values = chunk.iter().map(|(_, value)| value);
            let count = chunk.len();
            quote!(let [#(#names),*]: [f64; #count] = [#(#values),*];)
        })
        .collect()
}

fn prologue_item(item: &Prologue, read: &HashSet<usize>, top: bool) -> TokenStream {
    match item {
        Prologue::Stmt(stmt) => stmt.to_token_stream(),
        Prologue::Opaque(i, _) if !read.contains(i) => TokenStream::new(),
        Prologue::Opaque(i, tokens) => {
            let name = opaque_ident(*i);
            if top {
                quote!(let #name: f64 = #tokens;)
            } else {
                quote!(#name = #tokens;)
            }
        }
        Prologue::Scope(items) => {
            let items = items.iter().map(|p| prologue_item(p, read, false));
            quote!({ #(#items)* })
        }
        Prologue::Branch(branch) => {
            let selector = selector_ident(branch.selector);
            let arms: Vec<TokenStream> = branch
                .arms
                .iter()
                .enumerate()
                .map(|(k, arm)| {
                    let items = arm.iter().map(|p| prologue_item(p, read, false));
                    match branch.kind {
                        BranchKind::Every => quote!({ #(#items)* }),
                        _ => quote!({ #(#items)* #selector = #k; }),
                    }
                })
                .collect();
            match &branch.kind {
                BranchKind::Every => quote!(#(#arms)*),
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

#[cfg(test)]
mod tests {
    use quote::quote;

    use super::{RUN, opaques_read, prologue_tokens};
    use crate::generate::code::tests::Scopes;
    use crate::ir::Graph;
    use crate::lower::Prologue;

    /// The prologue computes only the opaque values the generated code reads: a state-free local
    /// of another type (`let n = self.count;`, a `usize`) is not an `f64` to compute.
    #[test]
    fn the_prologue_computes_what_is_read() {
        let mut graph = Graph::default();
        graph.opaque(0);
        let (k, x) = (graph.opaque(1), graph.var(0));
        let root = graph.mul(k, x);
        let read = opaques_read(&graph, &[root]);
        assert_eq!(read, [1].into());
        let prologue = [
            Prologue::Opaque(0, quote!(self.count)),
            Prologue::Opaque(1, quote!(self.k)),
        ];
        let statements = prologue_tokens(&prologue, &read);
        assert_eq!(statements.len(), 1);
        assert!(statements[0].to_string().contains("self . k"));
    }

    /// Opaque values set in the arms of a branch are declared before it, `RUN` to a `let` when
    /// there are more than `RUN`.
    #[test]
    fn many_values_set_in_branches_share_declarations() {
        let arm: Vec<Prologue> = (0..2 * RUN)
            .map(|i| Prologue::Opaque(i, quote!(self.k)))
            .collect();
        let branch = crate::lower::Branch {
            selector: 0,
            kind: crate::lower::BranchKind::If(vec![syn::parse_quote!(self.flag)]),
            arms: vec![arm, Vec::new()],
        };
        let all = (0..2 * RUN).collect();
        let statements = prologue_tokens(&[Prologue::Branch(Box::new(branch))], &all);
        // The selector, two lets of values, the branch.
        assert_eq!(statements.len(), 4);
        let scopes = Scopes::of(&statements);
        assert!(scopes.unbound.is_empty(), "{:?}", scopes.unbound);
    }

    /// Many opaque values at the top of the prologue are bound `RUN` to a `let`.
    #[test]
    fn many_opaque_values_share_lets() {
        let few: Vec<Prologue> = (0..RUN)
            .map(|i| Prologue::Opaque(i, quote!(self.k)))
            .collect();
        let all = (0..4 * RUN).collect();
        assert_eq!(prologue_tokens(&few, &all).len(), RUN);
        let many: Vec<Prologue> = (0..3 * RUN + 1)
            .map(|i| Prologue::Opaque(i, quote!(self.k)))
            .collect();
        let statements = prologue_tokens(&many, &all);
        assert_eq!(statements.len(), 4);
        let scopes = Scopes::of(&statements);
        assert_eq!(scopes.deepest, 4);
    }
}
