//! Transcendental calls routed through `odyn::math`: `x.sin()` in a model's code becomes
//! `::odyn::math::Transcendental::sin(x)`, so the `deterministic` feature can swap every such
//! function for the same pure-Rust implementation on every platform (see `runtime/src/math.rs`).
//! Without the feature the trait calls the float type's own method: the same value, the same
//! code after inlining.
//!
//! Applied to everything generated code evaluates: the rewritten bodies ([`crate::rewrite`]), the
//! prologue's copies of the user's state-free code, and the derivative code written from the IR.
//! `sqrt`, `abs` and `powi` are left alone (exact, or the same multiplications everywhere).

use proc_macro2::TokenStream;
use quote::{ToTokens, quote, quote_spanned};
use syn::visit_mut::{self, VisitMut};
use syn::{Block, Expr};

/// The one-argument methods `odyn::math::Transcendental` provides.
const UNARY: [&str; 20] = [
    "sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "asinh", "acosh", "atanh",
    "exp", "exp2", "exp_m1", "ln", "ln_1p", "log2", "log10", "cbrt",
];

/// The two-argument ones (`self` and one more).
const BINARY: [&str; 4] = ["powf", "atan2", "hypot", "log"];

/// Whether `method` with `args` further arguments is routed.
pub(crate) fn routed(method: &str, args: usize) -> bool {
    match args {
        0 => UNARY.contains(&method),
        1 => BINARY.contains(&method),
        _ => false,
    }
}

/// The call of `method` on `receiver` with `args` through `odyn::math`, spanned at `method`.
pub(crate) fn call(
    method: &syn::Ident,
    receiver: TokenStream,
    args: &[TokenStream],
) -> TokenStream {
    quote_spanned!(method.span()=> ::odyn::math::Transcendental::#method(#receiver #(, #args)*))
}

/// `block` with its transcendental calls routed.
pub(crate) fn route_block(block: &mut Block) {
    Router.visit_block_mut(block);
}

/// Statements (`let`s, branches) with their transcendental calls routed; tokens that do not parse
/// as statements are returned unchanged (the compiler then reports them as written).
pub(crate) fn route_statements(tokens: TokenStream) -> TokenStream {
    match syn::parse2::<Block>(quote!({ #tokens })) {
        Ok(mut block) => {
            route_block(&mut block);
            let statements = block.stmts;
            quote!(#(#statements)*)
        }
        Err(_) => tokens,
    }
}

/// Replaces `x.sin()` and `f64::sin(x)` (and `f32::`) with their `odyn::math` calls.
struct Router;

impl VisitMut for Router {
    fn visit_expr_mut(&mut self, expr: &mut Expr) {
        visit_mut::visit_expr_mut(self, expr);
        let routed_call = match &*expr {
            Expr::MethodCall(m)
                if m.turbofish.is_none() && routed(&m.method.to_string(), m.args.len()) =>
            {
                let args: Vec<_> = m.args.iter().map(ToTokens::to_token_stream).collect();
                // `(2.0 * t).sin()`: an argument needs no parentheses (rustc would warn of them
                // in the user's own helper methods, which are emitted routed).
                let receiver = match &*m.receiver {
                    Expr::Paren(p) => p.expr.to_token_stream(),
                    other => other.to_token_stream(),
                };
                Some(call(&m.method, receiver, &args))
            }
            Expr::Call(c) => float_function(&c.func).and_then(|method| {
                let mut args = c.args.iter().map(ToTokens::to_token_stream);
                let receiver = args.next()?;
                let rest: Vec<_> = args.collect();
                routed(&method.to_string(), rest.len()).then(|| call(&method, receiver, &rest))
            }),
            _ => None,
        };
        if let Some(tokens) = routed_call
            && let Ok(routed) = syn::parse2(tokens)
        {
            *expr = routed;
        }
    }
}

/// `name` of a path `f64::name` or `f32::name`.
fn float_function(func: &Expr) -> Option<syn::Ident> {
    let Expr::Path(path) = func else { return None };
    if path.qself.is_some() {
        return None;
    }
    let segments: Vec<_> = path.path.segments.iter().collect();
    match segments.as_slice() {
        [ty, name] if (ty.ident == "f64" || ty.ident == "f32") && name.arguments.is_none() => {
            Some(name.ident.clone())
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use quote::quote;

    use super::route_statements;

    /// Method and path calls of the listed functions are routed, receivers and arguments
    /// whole; exact functions, unknown methods and wrong arities are not.
    #[test]
    fn routes_the_transcendental_calls_only() {
        let routed = route_statements(quote! {
            let a = (x + 1.0).sin() * y.powf(2.5) + f64::atan2(y, x);
            let b = x.sqrt() + x.powi(3) + x.abs() + x.norm() + x.sin_cos().0 + x.powf(1.0, 2.0);
        })
        .to_string();
        let expected = quote! {
            let a = ::odyn::math::Transcendental::sin(x + 1.0)
                * ::odyn::math::Transcendental::powf(y, 2.5)
                + ::odyn::math::Transcendental::atan2(y, x);
            let b = x.sqrt() + x.powi(3) + x.abs() + x.norm() + x.sin_cos().0 + x.powf(1.0, 2.0);
        }
        .to_string();
        assert_eq!(routed, expected);
    }

    /// Calls inside calls are routed from the inside out.
    #[test]
    fn routes_nested_calls() {
        let routed = route_statements(quote!(let c = x.exp().ln();)).to_string();
        let expected = quote! {
            let c = ::odyn::math::Transcendental::ln(::odyn::math::Transcendental::exp(x));
        }
        .to_string();
        assert_eq!(routed, expected);
    }
}
