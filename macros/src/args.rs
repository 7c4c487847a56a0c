//! Stage 1: the arguments of `#[system(integrator = ..., dt = ...)]`.

use proc_macro2::TokenStream;
use syn::parse::Parser;
use syn::{Expr, Ident, Lit};

use crate::errors::Errors;

/// What the macro knows of a method: enough to reject a model it cannot integrate.
pub(crate) struct MethodInfo {
    /// The `odyn::Method` variant.
    pub(crate) name: &'static str,
    pub(crate) needs_second_order: bool,
    pub(crate) needs_velocity_free_forces: bool,
}

/// The methods an attribute may name, mirroring `odyn::Method`.
const METHODS: [MethodInfo; 7] = [
    MethodInfo {
        name: "ExplicitEuler",
        needs_second_order: false,
        needs_velocity_free_forces: false,
    },
    MethodInfo {
        name: "SymplecticEuler",
        needs_second_order: true,
        needs_velocity_free_forces: false,
    },
    MethodInfo {
        name: "PositionVerlet",
        needs_second_order: true,
        needs_velocity_free_forces: true,
    },
    MethodInfo {
        name: "VelocityVerlet",
        needs_second_order: true,
        needs_velocity_free_forces: false,
    },
    MethodInfo {
        name: "Leapfrog",
        needs_second_order: true,
        needs_velocity_free_forces: false,
    },
    MethodInfo {
        name: "Rk4",
        needs_second_order: false,
        needs_velocity_free_forces: false,
    },
    MethodInfo {
        name: "ImplicitEuler",
        needs_second_order: false,
        needs_velocity_free_forces: false,
    },
];

/// The parsed arguments.
#[derive(Default)]
pub(crate) struct Args {
    /// `integrator = Name`, with the token for error spans.
    pub(crate) integrator: Option<(Ident, &'static MethodInfo)>,
    /// `dt = <expr>`: a literal is checked here, any other constant expression at run time.
    pub(crate) dt: Option<Expr>,
    /// `jacobian = false` opts out of the generated Jacobian (and so of implicit methods).
    pub(crate) no_jacobian: Option<syn::LitBool>,
}

/// Parses the attribute's arguments, reporting problems to `errors`.
pub(crate) fn parse(tokens: TokenStream, errors: &mut Errors) -> Args {
    let mut args = Args::default();
    let parser = syn::meta::parser(|meta| {
        if meta.path.is_ident("integrator") {
            let ident: Ident = meta.value()?.parse()?;
            match METHODS.iter().find(|m| ident == m.name) {
                Some(info) => args.integrator = Some((ident, info)),
                None => errors.at(
                    &ident,
                    format_args!("unknown integrator `{ident}`; supported: {}", names()),
                ),
            }
            Ok(())
        } else if meta.path.is_ident("dt") {
            let expr: Expr = meta.value()?.parse()?;
            check_dt(&expr, errors);
            args.dt = Some(expr);
            Ok(())
        } else if meta.path.is_ident("jacobian") {
            let value: syn::LitBool = meta.value()?.parse()?;
            if !value.value {
                args.no_jacobian = Some(value);
            }
            Ok(())
        } else {
            Err(meta.error(format_args!(
                "unknown `#[system]` argument `{}`; supported: `integrator = ...`, `dt = ...`, \
                 `jacobian = false`",
                meta.path
                    .get_ident()
                    .map_or_else(|| "?".to_owned(), Ident::to_string)
            )))
        }
    });
    if let Err(error) = parser.parse2(tokens) {
        errors.push(error);
    }
    args
}

fn names() -> String {
    METHODS
        .iter()
        .map(|m| format!("`{}`", m.name))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A literal dt must be finite and positive; anything else is left to the run-time check.
fn check_dt(expr: &Expr, errors: &mut Errors) {
    if let Expr::Unary(syn::ExprUnary {
        op: syn::UnOp::Neg(_),
        ..
    }) = expr
    {
        errors.at(expr, "`dt` must be finite and positive");
        return;
    }
    let Expr::Lit(lit) = expr else { return };
    let value = match &lit.lit {
        Lit::Float(f) => f.base10_parse::<f64>().ok(),
        Lit::Int(i) => i.base10_parse::<f64>().ok(),
        _ => {
            errors.at(lit, "`dt` must be a number of seconds, such as `dt = 0.01`");
            return;
        }
    };
    match value {
        Some(v) if v.is_finite() && v > 0.0 => {}
        _ => errors.at(lit, "`dt` must be finite and positive"),
    }
}
