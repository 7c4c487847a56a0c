use proc_macro2::TokenStream;
use quote::quote;
use syn::visit::{self, Visit};

use super::{RUN, straight_line};
use crate::ir::{ExprId, Graph};

/// Walks generated statements: how deep `let` scopes nest, and reads of `__odyn_*` names
/// with no binding in scope.
#[derive(Default)]
pub(in crate::generate) struct Scopes {
    /// Names in scope, innermost last, and how many times each is bound.
    bound: Vec<String>,
    count: std::collections::HashMap<String, usize>,
    depth: usize,
    pub(in crate::generate) deepest: usize,
    pub(in crate::generate) unbound: Vec<String>,
}

impl Scopes {
    pub(in crate::generate) fn of(statements: &[TokenStream]) -> Scopes {
        let block: syn::Block = syn::parse2(quote!({ #(#statements)* })).unwrap();
        let mut scopes = Scopes::default();
        scopes.visit_block(&block);
        scopes
    }
}

impl<'ast> Visit<'ast> for Scopes {
    fn visit_block(&mut self, block: &'ast syn::Block) {
        let (bound, depth) = (self.bound.len(), self.depth);
        for stmt in &block.stmts {
            match stmt {
                syn::Stmt::Local(local) => {
                    if let Some(init) = &local.init {
                        self.visit_expr(&init.expr);
                    }
                    for name in names(&local.pat) {
                        *self.count.entry(name.clone()).or_default() += 1;
                        self.bound.push(name);
                    }
                    self.depth += 1;
                    self.deepest = self.deepest.max(self.depth);
                }
                other => self.visit_stmt(other),
            }
        }
        for name in self.bound.drain(bound..) {
            *self.count.get_mut(&name).expect("counted when bound") -= 1;
        }
        self.depth = depth;
    }

    fn visit_ident(&mut self, ident: &'ast proc_macro2::Ident) {
        let name = ident.to_string();
        if name.starts_with("__odyn_") && self.count.get(&name).is_none_or(|&n| n == 0) {
            self.unbound.push(name);
        }
        visit::visit_ident(self, ident);
    }
}

/// The names a `let` pattern binds.
fn names(pat: &syn::Pat) -> Vec<String> {
    struct Names(Vec<String>);
    impl<'ast> Visit<'ast> for Names {
        fn visit_pat_ident(&mut self, p: &'ast syn::PatIdent) {
            self.0.push(p.ident.to_string());
        }
    }
    let mut names = Names(Vec::new());
    names.visit_pat(pat);
    names.0
}

/// xᵢ = xᵢ₋₁·v + i from x₀ = u: a chain of `2·steps` operations, every one read by the next.
fn chain(graph: &mut Graph, steps: usize) -> Vec<ExprId> {
    let (u, v) = (graph.var(0), graph.var(1));
    let mut xs = vec![u];
    for i in 1..=steps {
        let scaled = graph.mul(xs[i - 1], v);
        let step = graph.num(i as f64);
        xs.push(graph.add(scaled, step));
    }
    xs
}

#[test]
fn short_straight_line_is_one_let_per_value() {
    let mut graph = Graph::default();
    let xs = chain(&mut graph, RUN / 2);
    let components = [quote!(u), quote!(v)];
    let lets = straight_line(&graph, &[xs[RUN / 2]], &components);
    assert_eq!(lets.len(), RUN);
    let scopes = Scopes::of(&lets);
    assert_eq!(scopes.deepest, RUN);
    assert!(scopes.unbound.is_empty(), "{:?}", scopes.unbound);
}

/// Past a run's length the `let`s go in blocks, and blocks of blocks past its square (here
/// runs of 4 in place of 256, so three levels of blocks cost little): scopes nest a few runs
/// deep, and every value read after its block is handed on.
#[test]
fn long_straight_line_nests_in_blocks() {
    let mut graph = Graph::default();
    let steps = 150;
    let xs = chain(&mut graph, steps);
    let components = [quote!(u), quote!(v)];
    // Early and middle values read after the straight line, as a Jacobian's entries are.
    let roots = [xs[steps], xs[1], xs[steps / 2], xs[17]];
    let ids = graph.reachable(roots);
    let lets = super::lets_in_runs(&graph, &ids, &components, &roots, 4);
    let scopes = Scopes::of(&lets);
    // 300 values: blocks of 75, 19, 5 and 4 values, up to 4 `let`s deep at each level.
    assert!(scopes.deepest <= 4 * 5, "{}", scopes.deepest);
    let roots = roots.map(|id| super::operand(&graph, id, &components));
    let read = quote!({ #(#lets)* [#(#roots),*] });
    let scopes = Scopes::of(&[read]);
    assert!(scopes.unbound.is_empty(), "{:?}", scopes.unbound);
}
