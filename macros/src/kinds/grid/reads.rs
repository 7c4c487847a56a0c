//! Stencil reads as scalar inputs: `u.e` becomes the input `u__e`, and `u.laplacian()` the sum
//! it stands for, so the shared lowering sees a function of numbers. Any other use of a stencil
//! is an error at its token.

use quote::{ToTokens, format_ident, quote_spanned};
use syn::spanned::Spanned;
use syn::visit_mut::{self, VisitMut};
use syn::{Expr, Ident, ImplItemFn, Member};

use super::NEIGHBOURS;
use crate::errors::Errors;

/// The scalar input standing for neighbour `neighbour` of `stencil`.
pub(super) fn input(stencil: &Ident, neighbour: &str) -> Ident {
    format_ident!("{}__{}", stencil, neighbour, span = stencil.span())
}

/// `f` with every stencil read renamed (see the module docs).
pub(super) fn rename(
    f: &ImplItemFn,
    stencils: &[(Ident, usize)],
    errors: &mut Errors,
) -> ImplItemFn {
    let mut f = f.clone();
    let mut renamer = Renamer {
        stencils: stencils.iter().map(|(s, _)| s).collect(),
        errors,
    };
    renamer.visit_block_mut(&mut f.block);
    f
}

struct Renamer<'a, 'e> {
    stencils: Vec<&'a Ident>,
    errors: &'e mut Errors,
}

impl Renamer<'_, '_> {
    /// The stencil `e` names, if it is a bare stencil argument.
    fn stencil(&self, e: &Expr) -> Option<Ident> {
        let Expr::Path(p) = e else { return None };
        let ident = p.path.get_ident()?;
        self.stencils.contains(&ident).then(|| ident.clone())
    }

    fn neighbours() -> String {
        NEIGHBOURS
            .iter()
            .map(|n| format!("`.{n}`"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

impl VisitMut for Renamer<'_, '_> {
    fn visit_expr_mut(&mut self, e: &mut Expr) {
        match e {
            Expr::Field(field) => {
                if let Some(stencil) = self.stencil(&field.base) {
                    let name = match &field.member {
                        Member::Named(n) => n.to_string(),
                        Member::Unnamed(i) => i.index.to_string(),
                    };
                    if NEIGHBOURS.contains(&name.as_str()) {
                        let ident = input(&stencil, &name);
                        *e = syn::parse_quote_spanned!(field.span()=> #ident);
                    } else {
                        self.errors.at(
                            &field.member,
                            format_args!(
                                "a stencil has no neighbour `{name}`; `{stencil}` has {}",
                                Self::neighbours()
                            ),
                        );
                    }
                    return;
                }
            }
            Expr::MethodCall(call) => {
                if let Some(stencil) = self.stencil(&call.receiver) {
                    if call.method == "laplacian" && call.args.is_empty() {
                        let [c, east, west, north, south] =
                            ["c", "e", "w", "n", "s"].map(|n| input(&stencil, n));
                        let span = call.span();
                        *e = syn::parse2(quote_spanned!(span=>
                            (#east + #west + #north + #south - 4.0 * #c)))
                        .expect("a sum of names parses");
                    } else {
                        self.errors.at(
                            &call.method,
                            format_args!(
                                "a stencil has one method, `{stencil}.laplacian()`; read its \
                                 values as {}",
                                Self::neighbours()
                            ),
                        );
                    }
                    return;
                }
            }
            Expr::Path(_) => {
                if let Some(stencil) = self.stencil(e) {
                    self.errors.at(
                        e.to_token_stream(),
                        format_args!(
                            "a stencil is read through its neighbours, {} (or \
                             `{stencil}.laplacian()`), not used whole",
                            Self::neighbours()
                        ),
                    );
                    return;
                }
            }
            _ => {}
        }
        visit_mut::visit_expr_mut(self, e);
    }
}
