//! Stage 1: the arguments of `#[system(integrator = ..., dt = ...)]`.

use proc_macro2::TokenStream;
use syn::parse::Parser;
use syn::{Expr, Ident, Lit};

use crate::errors::Errors;

/// What the macro knows of a method: enough to reject a model it cannot integrate.
#[derive(Clone, Copy)]
pub(crate) struct MethodNeeds {
    /// The `odyn::Method` variant.
    pub(crate) name: &'static str,
    pub(crate) needs_second_order: bool,
    pub(crate) needs_velocity_free_forces: bool,
    /// Whether it steps to tolerances (so `rtol`/`atol` apply to it).
    pub(crate) adaptive: bool,
    /// Whether it needs the generated Jacobian (which `jacobian = false` turns off).
    pub(crate) needs_jacobian: bool,
}

const fn method(row: odyn_methods::MethodRow) -> MethodNeeds {
    use odyn_methods::Needs;
    MethodNeeds {
        name: row.variant,
        needs_second_order: matches!(row.needs, Needs::Split | Needs::VelocityFree),
        needs_velocity_free_forces: matches!(row.needs, Needs::VelocityFree),
        adaptive: row.adaptive,
        needs_jacobian: matches!(row.needs, Needs::Jacobian),
    }
}

/// The methods an attribute may name: the rows of the one table of methods (`odyn-methods`),
/// which `odyn::Method` is generated from too.
const METHODS: [MethodNeeds; odyn_methods::METHODS.len()] = {
    let rows = odyn_methods::METHODS;
    let mut out = [method(rows[0]); odyn_methods::METHODS.len()];
    let mut i = 1;
    while i < rows.len() {
        out[i] = method(rows[i]);
        i += 1;
    }
    out
};

/// The parsed arguments.
#[derive(Default)]
pub(crate) struct Args {
    /// `integrator = Name`, with the token for error spans.
    pub(crate) integrator: Option<(Ident, &'static MethodNeeds)>,
    /// `dt = <expr>`: a literal expression is checked here, any other constant expression by a
    /// `const` assertion in the generated code.
    pub(crate) dt: Option<Expr>,
    /// `rtol = <expr>`, checked like `dt`.
    pub(crate) rtol: Option<Expr>,
    /// `atol = <expr>`, checked like `dt`.
    pub(crate) atol: Option<Expr>,
    /// `jacobian = ...`: how the Jacobian is made.
    pub(crate) jacobian: JacobianKey,
}

/// How the model's Jacobian is made (`jacobian = ...`), with the token for error spans: one
/// value, so no combination of the forms can be represented.
#[derive(Clone, Default)]
pub(crate) enum JacobianKey {
    /// Generated exactly from the model's code: the default, or `jacobian = true`.
    #[default]
    Generated,
    /// `jacobian = false` opts out of the generated Jacobian (and so of implicit methods).
    Off(syn::LitBool),
    /// `jacobian = finite_differences`: a fixed-size model's Jacobian by central differences of
    /// its own code, for code the macro cannot differentiate.
    Differences(Ident),
    /// `jacobian = dual`: a fixed-size model's Jacobian by forward-mode automatic
    /// differentiation of its own code over dual numbers.
    Dual(Ident),
}

impl JacobianKey {
    /// The `false` of `jacobian = false`.
    pub(crate) fn off(&self) -> Option<&syn::LitBool> {
        match self {
            JacobianKey::Off(token) => Some(token),
            _ => None,
        }
    }

    /// The word of `jacobian = finite_differences`.
    pub(crate) fn differences(&self) -> Option<&Ident> {
        match self {
            JacobianKey::Differences(word) => Some(word),
            _ => None,
        }
    }

    /// The word of `jacobian = dual`.
    pub(crate) fn dual(&self) -> Option<&Ident> {
        match self {
            JacobianKey::Dual(word) => Some(word),
            _ => None,
        }
    }

    /// The word of a Jacobian made from the model's own code (`finite_differences` or `dual`).
    pub(crate) fn of_code(&self) -> Option<&Ident> {
        self.differences().or(self.dual())
    }
}

/// The arguments `#[system]` takes, for error messages.
const SUPPORTED: &str = "`integrator = ...`, `dt = ...`, `rtol = ...`, `atol = ...`, \
    `jacobian = false`, `jacobian = finite_differences`, `jacobian = dual`";

/// Parses the attribute's arguments, reporting problems to `errors`. A problem with one
/// argument hides none of the others: an unknown argument or a value of the wrong form is
/// reported and skipped, and parsing goes on after the next comma.
pub(crate) fn parse(tokens: TokenStream, errors: &mut Errors) -> Args {
    let mut args = Args::default();
    let mut seen: Vec<String> = Vec::new();
    let parser = syn::meta::parser(|meta| {
        let name = meta
            .path
            .get_ident()
            .map_or_else(|| "?".to_owned(), Ident::to_string);
        if seen.contains(&name) {
            errors.at(
                &meta.path,
                format_args!("`{name}` is given twice; give each argument once"),
            );
        }
        seen.push(name.clone());
        if ["integrator", "dt", "rtol", "atol", "jacobian"].contains(&name.as_str()) {
            let value: Expr = meta.value()?.parse()?;
            read(&name, value, &mut args, errors);
        } else {
            errors.push(meta.error(format_args!(
                "unknown `#[system]` argument `{name}`; supported: {SUPPORTED}"
            )));
            skip_to_comma(meta.input)?;
        }
        Ok(())
    });
    if let Err(error) = parser.parse2(tokens) {
        errors.push(error);
    }
    args
}

/// Reads the value of argument `name` into `args`.
fn read(name: &str, value: Expr, args: &mut Args, errors: &mut Errors) {
    match name {
        "integrator" => {
            let ident = match &value {
                Expr::Path(p) if p.qself.is_none() && p.attrs.is_empty() => p.path.get_ident(),
                _ => None,
            };
            let Some(ident) = ident else {
                errors.at(
                    &value,
                    format_args!(
                        "`integrator` takes a method's name, such as `integrator = Rk4`; \
                         supported: {}",
                        names()
                    ),
                );
                return;
            };
            match METHODS.iter().find(|m| ident == m.name) {
                Some(info) => args.integrator = Some((ident.clone(), info)),
                None => errors.at(
                    ident,
                    format_args!("unknown integrator `{ident}`; supported: {}", names()),
                ),
            }
        }
        "jacobian" => match &value {
            Expr::Lit(syn::ExprLit {
                lit: Lit::Bool(value),
                ..
            }) => {
                if !value.value {
                    args.jacobian = JacobianKey::Off(value.clone());
                }
            }
            Expr::Path(p) if p.path.is_ident("finite_differences") => {
                if let Some(word) = p.path.get_ident() {
                    args.jacobian = JacobianKey::Differences(word.clone());
                }
            }
            Expr::Path(p) if p.path.is_ident("dual") => {
                if let Some(word) = p.path.get_ident() {
                    args.jacobian = JacobianKey::Dual(word.clone());
                }
            }
            _ => errors.at(
                &value,
                "`jacobian` takes `false` (explicit methods only), `finite_differences` (a \
                 Jacobian of central differences of the model's code), `dual` (forward-mode \
                 automatic differentiation of the model's code) or `true` (the default: \
                 generated exactly)",
            ),
        },
        _ => {
            check_number(name, &value, errors);
            let slot = match name {
                "dt" => &mut args.dt,
                "rtol" => &mut args.rtol,
                _ => &mut args.atol,
            };
            *slot = Some(value);
        }
    }
}

/// Moves `input` to the next comma (or its end), past an argument that was not understood.
fn skip_to_comma(input: syn::parse::ParseStream<'_>) -> syn::Result<()> {
    input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((tree, next)) = rest.token_tree() {
            if matches!(&tree, proc_macro2::TokenTree::Punct(p) if p.as_char() == ',') {
                break;
            }
            rest = next;
        }
        Ok(((), rest))
    })
}

fn names() -> String {
    METHODS
        .iter()
        .map(|m| format!("`{}`", m.name))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The adaptive integrators' names, for messages.
pub(crate) fn adaptive_names() -> String {
    METHODS
        .iter()
        .filter(|m| m.adaptive)
        .map(|m| format!("`{}`", m.name))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A `dt`, `rtol` or `atol` made of literals must be a positive number (`rtol` and `atol` may be
/// zero); integer division, which Rust rounds towards zero, is refused outright. Anything else
/// (a `const`, a path) is checked by a `const` assertion in the generated code.
fn check_number(name: &str, expr: &Expr, errors: &mut Errors) {
    let zero_allowed = name != "dt";
    let requirement = if zero_allowed {
        "finite and non-negative"
    } else {
        "finite and positive"
    };
    match evaluate(expr) {
        Ok(Some(value)) => {
            let ok = value.is_finite() && (value > 0.0 || (zero_allowed && value == 0.0));
            if !ok {
                errors.at(
                    expr,
                    format_args!("`{name}` must be {requirement}; this is {value:?}"),
                );
            }
        }
        Ok(None) => {}
        Err((span, message)) => errors.at(span, format_args!("`{name}`: {message}")),
    }
}

/// The value of an expression made of number literals, `+ - * /`, unary minus and parentheses;
/// `Ok(None)` for anything else. Integer arithmetic follows Rust's, so `1/60` is refused as the
/// integer division it is.
fn evaluate(expr: &Expr) -> Result<Option<f64>, (&Expr, String)> {
    enum Number {
        Int(i128),
        Float(f64),
    }
    fn eval(expr: &Expr) -> Result<Option<Number>, (&Expr, String)> {
        Ok(Some(match expr {
            Expr::Lit(lit) => match &lit.lit {
                Lit::Int(i) => match i.base10_parse::<i128>() {
                    Ok(v) => Number::Int(v),
                    Err(_) => return Ok(None),
                },
                Lit::Float(f) => match f.base10_parse::<f64>() {
                    Ok(v) => Number::Float(v),
                    Err(_) => return Ok(None),
                },
                _ => {
                    return Err((expr, "must be a number, such as `0.01`".to_owned()));
                }
            },
            Expr::Paren(p) => return eval(&p.expr),
            Expr::Group(g) => return eval(&g.expr),
            Expr::Unary(u) if matches!(u.op, syn::UnOp::Neg(_)) => match eval(&u.expr)? {
                Some(Number::Int(v)) => return Ok(v.checked_neg().map(Number::Int)),
                Some(Number::Float(v)) => Number::Float(-v),
                None => return Ok(None),
            },
            Expr::Binary(b) => {
                let (Some(l), Some(r)) = (eval(&b.left)?, eval(&b.right)?) else {
                    return Ok(None);
                };
                match (l, r) {
                    (Number::Int(l), Number::Int(r)) => match b.op {
                        // An overflow is left to the compiler's own const evaluation.
                        syn::BinOp::Add(_) => return Ok(l.checked_add(r).map(Number::Int)),
                        syn::BinOp::Sub(_) => return Ok(l.checked_sub(r).map(Number::Int)),
                        syn::BinOp::Mul(_) => return Ok(l.checked_mul(r).map(Number::Int)),
                        syn::BinOp::Div(_) => {
                            return Err((
                                expr,
                                "divides integers, which rounds towards zero in Rust (`1/60` \
                                 is 0); write float literals, such as `1.0 / 60.0`"
                                    .to_owned(),
                            ));
                        }
                        _ => return Ok(None),
                    },
                    (l, r) => {
                        let as_f64 = |n| match n {
                            Number::Int(v) => v as f64,
                            Number::Float(v) => v,
                        };
                        let (l, r) = (as_f64(l), as_f64(r));
                        match b.op {
                            syn::BinOp::Add(_) => Number::Float(l + r),
                            syn::BinOp::Sub(_) => Number::Float(l - r),
                            syn::BinOp::Mul(_) => Number::Float(l * r),
                            syn::BinOp::Div(_) => Number::Float(l / r),
                            _ => return Ok(None),
                        }
                    }
                }
            }
            _ => return Ok(None),
        }))
    }
    Ok(eval(expr)?.map(|n| match n {
        Number::Int(v) => v as f64,
        Number::Float(v) => v,
    }))
}

#[cfg(test)]
mod tests {
    use quote::quote;

    use crate::errors::Errors;

    /// One problem per argument, each reported: none hides the ones after it.
    #[test]
    fn every_argument_error_is_kept() {
        let mut errors = Errors::default();
        let args = super::parse(
            quote!(
                tolerance = 1e-6,
                integrator = Rk5,
                jacobian = 1,
                dt = 1 / 60,
                rtol = 1e-6
            ),
            &mut errors,
        );
        assert_eq!(errors.len(), 4);
        assert!(args.rtol.is_some());
        let mut errors = Errors::default();
        super::parse(
            quote!(integrator = odyn::Method::Rk4, foo(1, 2), atol = -1.0),
            &mut errors,
        );
        assert_eq!(errors.len(), 3);
    }
}
