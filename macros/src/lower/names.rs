//! What code names and may change, read from its syntax alone: the targets of assignments and
//! `&mut` borrows, the names a pattern or a `let` condition binds, `return`s that leave the
//! function, and identifiers in token streams.

use proc_macro2::TokenStream;
use syn::visit::{self, Visit};
use syn::{Expr, Ident, Pat};

/// Every name the code it visits may change, bound or not: the plain-name targets of `=` and
/// `op=` (through an index or a field), method-call receivers and `&mut` borrows.
#[derive(Default)]
pub(super) struct Targets(pub(super) Vec<Ident>);

impl Targets {
    fn target(&mut self, e: &Expr) {
        // `w[k][0].x = …` changes `w`.
        let mut base = e;
        loop {
            base = match base {
                Expr::Index(i) => &i.expr,
                Expr::Field(f) => &f.base,
                Expr::Paren(p) => &p.expr,
                _ => break,
            };
        }
        if let Expr::Path(p) = base
            && let Some(ident) = p.path.get_ident()
        {
            self.0.push(ident.clone());
        }
    }
}

impl<'ast> Visit<'ast> for Targets {
    fn visit_expr(&mut self, e: &'ast Expr) {
        match e {
            Expr::Assign(a) => self.target(&a.left),
            Expr::Binary(b) if super::compound(&b.op).is_some() => self.target(&b.left),
            Expr::MethodCall(m) => self.target(&m.receiver),
            Expr::Reference(r) if r.mutability.is_some() => self.target(&r.expr),
            _ => {}
        }
        visit::visit_expr(self, e);
    }
}

/// The names a pattern binds.
pub(super) fn pattern_names(pat: &Pat) -> Vec<String> {
    struct Names(Vec<String>);
    impl<'ast> Visit<'ast> for Names {
        fn visit_pat_ident(&mut self, p: &'ast syn::PatIdent) {
            self.0.push(p.ident.to_string());
            visit::visit_pat_ident(self, p);
        }
    }
    let mut names = Names(Vec::new());
    names.visit_pat(pat);
    names.0
}

/// Whether `stmts` contain a `return` that leaves the function (not one inside a closure or a
/// nested item).
pub(super) fn returns(stmts: &[syn::Stmt]) -> bool {
    struct Finder(bool);
    impl<'ast> Visit<'ast> for Finder {
        fn visit_expr_return(&mut self, _: &'ast syn::ExprReturn) {
            self.0 = true;
        }
        fn visit_expr_closure(&mut self, _: &'ast syn::ExprClosure) {}
        fn visit_item(&mut self, _: &'ast syn::Item) {}
        fn visit_expr_async(&mut self, _: &'ast syn::ExprAsync) {}
    }
    let mut finder = Finder(false);
    for stmt in stmts {
        finder.visit_stmt(stmt);
    }
    finder.0
}

pub(super) fn path_name(e: &Expr) -> Option<String> {
    match e {
        Expr::Path(p) if p.qself.is_none() => p.path.get_ident().map(Ident::to_string),
        _ => None,
    }
}

/// The names `let` conditions in `cond` bind (`if let Some(x) = …`).
pub(super) fn let_names(cond: &Expr) -> Vec<String> {
    struct Lets(Vec<String>);
    impl<'ast> syn::visit::Visit<'ast> for Lets {
        fn visit_expr_let(&mut self, l: &'ast syn::ExprLet) {
            self.0.extend(pattern_names(&l.pat));
        }
    }
    let mut lets = Lets(Vec::new());
    syn::visit::Visit::visit_expr(&mut lets, cond);
    lets.0
}

/// Whether any identifier in `tokens`, groups included, passes `test`.
pub(super) fn any_ident(tokens: &TokenStream, test: &dyn Fn(&proc_macro2::Ident) -> bool) -> bool {
    tokens.clone().into_iter().any(|tree| match tree {
        proc_macro2::TokenTree::Ident(i) => test(&i),
        proc_macro2::TokenTree::Group(g) => any_ident(&g.stream(), test),
        _ => false,
    })
}
