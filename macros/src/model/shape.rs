//! The shapes of state fields and of their lengths (`f64`, `[f64; N]`, `SVector<f64, N>`,
//! `[[f64; M]; N]`), as read from a field's type.

use proc_macro2::TokenStream;
use quote::quote;
use syn::{GenericArgument, Ident, PathArguments, Type};

use crate::syntax::{int_literal, is_f64};

/// A length in a state type: an integer literal, or a const parameter of a generic model
/// (`N` in `[f64; N]` of `struct Chain<const N: usize>`), by its position among the struct's
/// const parameters.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Len {
    Known(usize),
    Param(usize),
}

impl Len {
    /// The length, for code that lays out a concrete model: lowering, the Jacobian, the state's
    /// component names. None of it runs on a generic model ([`Model::is_generic`](crate::model::Model::is_generic): its code is
    /// emitted as written and its Jacobian taken by differences), so a parameter counts as 0.
    pub(crate) fn count(self) -> usize {
        match self {
            Len::Known(n) => n,
            Len::Param(_) => 0,
        }
    }

    /// The length in generated code: the literal, or the parameter's name.
    pub(crate) fn to_tokens(self, params: &[&Ident]) -> TokenStream {
        match self {
            Len::Known(n) => {
                let n = proc_macro2::Literal::usize_unsuffixed(n);
                quote!(#n)
            }
            Len::Param(i) => {
                let name = params.get(i);
                quote!(#name)
            }
        }
    }

    fn describe(self, params: &[&Ident]) -> String {
        match self {
            Len::Known(n) => n.to_string(),
            Len::Param(i) => params.get(i).map_or_else(String::new, ToString::to_string),
        }
    }
}

/// The shape of a state field's value.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Shape {
    /// `f64`
    Scalar,
    /// `[f64; N]`
    Array(Len),
    /// `SVector<f64, N>` or `VectorN<f64>`
    Vector(Len),
    /// `[[f64; M]; N]` or `[SVector<f64, M>; N]` (`[Vector3<f64>; N]`): `N` rows of `M`, laid out
    /// row after row.
    Rows(Len, Row),
}

/// One row of a [`Shape::Rows`].
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Row {
    /// `[f64; M]`
    Array(Len),
    /// `SVector<f64, M>` or `VectorM<f64>`
    Vector(Len),
}

impl Row {
    pub(crate) fn len(self) -> usize {
        match self {
            Row::Array(m) | Row::Vector(m) => m.count(),
        }
    }

    /// The row as a shape of its own.
    pub(crate) fn shape(self) -> Shape {
        match self {
            Row::Array(m) => Shape::Array(m),
            Row::Vector(m) => Shape::Vector(m),
        }
    }
}

impl Shape {
    /// Number of `f64` components of a concrete model's field ([`Len::count`]).
    pub(crate) fn len(self) -> usize {
        match self {
            Shape::Scalar => 1,
            Shape::Array(n) | Shape::Vector(n) => n.count(),
            Shape::Rows(n, row) => n.count() * row.len(),
        }
    }

    /// Whether a length is a const parameter of the model.
    pub(crate) fn is_generic(self) -> bool {
        match self {
            Shape::Scalar => false,
            Shape::Array(n) | Shape::Vector(n) => matches!(n, Len::Param(_)),
            Shape::Rows(n, row) => matches!(n, Len::Param(_)) || row.shape().is_generic(),
        }
    }

    /// The number of components in generated code: `3`, `N`, `(N * 3)`.
    pub(crate) fn len_tokens(self, params: &[&Ident]) -> TokenStream {
        match self {
            Shape::Scalar => quote!(1),
            Shape::Array(n) | Shape::Vector(n) => n.to_tokens(params),
            Shape::Rows(n, row) => {
                let (n, m) = (n.to_tokens(params), row.shape().len_tokens(params));
                quote!((#n * #m))
            }
        }
    }

    /// The canonical type, with absolute paths; lengths that are const parameters by the names
    /// in `params`.
    pub(crate) fn to_type(self, params: &[&Ident]) -> TokenStream {
        match self {
            Shape::Scalar => quote!(f64),
            Shape::Array(n) => {
                let n = n.to_tokens(params);
                quote!([f64; #n])
            }
            Shape::Vector(n) => {
                let n = n.to_tokens(params);
                quote!(::odyn::__private::nalgebra::SVector<f64, #n>)
            }
            Shape::Rows(rows, row) => {
                let (rows, row) = (rows.to_tokens(params), row.shape().to_type(params));
                quote!([#row; #rows])
            }
        }
    }

    pub(crate) fn describe(self, params: &[&Ident]) -> String {
        match self {
            Shape::Scalar => "f64".to_owned(),
            Shape::Array(n) => format!("[f64; {}]", n.describe(params)),
            Shape::Vector(n) => format!("SVector<f64, {}>", n.describe(params)),
            Shape::Rows(n, row) => {
                format!("[{}; {}]", row.shape().describe(params), n.describe(params))
            }
        }
    }

    /// The component names of a field `name` of this shape, in layout order: `x`, `x[2]`,
    /// `x[2][1]`.
    pub(crate) fn component_names(self, name: &str) -> Vec<String> {
        match self {
            Shape::Scalar => vec![name.to_owned()],
            Shape::Array(n) | Shape::Vector(n) => {
                (0..n.count()).map(|i| format!("{name}[{i}]")).collect()
            }
            Shape::Rows(n, row) => (0..n.count())
                .flat_map(|i| (0..row.len()).map(move |j| format!("{name}[{i}][{j}]")))
                .collect(),
        }
    }

    /// How each component of a value `base` of this shape is read, in layout order: `base`,
    /// `base[2]`, `base[2][1]`.
    pub(crate) fn component_reads(self, base: &TokenStream) -> Vec<TokenStream> {
        match self {
            Shape::Scalar => vec![base.clone()],
            Shape::Array(n) | Shape::Vector(n) => {
                (0..n.count()).map(|i| quote!(#base[#i])).collect()
            }
            Shape::Rows(n, row) => (0..n.count())
                .flat_map(|i| (0..row.len()).map(move |j| quote!(#base[#i][#j])))
                .collect(),
        }
    }
}

/// The shape of a supported state type whose lengths are integer literals.
pub(crate) fn shape_of(ty: &Type) -> Option<Shape> {
    shape_in(ty, &[])
}

/// The shape of a supported state type whose lengths are integer literals or the const
/// parameters `params` of a generic model.
pub(crate) fn shape_in(ty: &Type, params: &[&Ident]) -> Option<Shape> {
    match ty {
        Type::Paren(p) => shape_in(&p.elem, params),
        Type::Group(g) => shape_in(&g.elem, params),
        Type::Array(a) if is_f64(&a.elem) => length(&a.len, params).map(Shape::Array),
        Type::Array(a) => {
            let row = match shape_in(&a.elem, params)? {
                Shape::Array(m) => Row::Array(m),
                Shape::Vector(m) => Row::Vector(m),
                Shape::Scalar | Shape::Rows(..) => return None,
            };
            length(&a.len, params).map(|n| Shape::Rows(n, row))
        }
        Type::Path(p) if p.qself.is_none() => {
            let last = p.path.segments.last()?;
            let name = last.ident.to_string();
            if name == "f64" {
                return (p.path.segments.len() == 1 && last.arguments.is_none())
                    .then_some(Shape::Scalar);
            }
            let PathArguments::AngleBracketed(args) = &last.arguments else {
                return None;
            };
            let args: Vec<_> = args.args.iter().collect();
            match (name.as_str(), args.as_slice()) {
                ("SVector", [GenericArgument::Type(t), GenericArgument::Const(n)]) if is_f64(t) => {
                    length(n, params).map(Shape::Vector)
                }
                // `SVector<f64, N>`: a bare name parses as a type.
                (
                    "SVector",
                    [
                        GenericArgument::Type(t),
                        GenericArgument::Type(Type::Path(n)),
                    ],
                ) if is_f64(t) && n.qself.is_none() => {
                    let name = n.path.get_ident()?;
                    param_index(name, params).map(|i| Shape::Vector(Len::Param(i)))
                }
                (vector, [GenericArgument::Type(t)]) if is_f64(t) => vector
                    .strip_prefix("Vector")
                    .and_then(|n| n.parse::<usize>().ok())
                    .filter(|n| (1..=6).contains(n))
                    .map(|n| Shape::Vector(Len::Known(n))),
                _ => None,
            }
        }
        _ => None,
    }
}

/// An array length: an integer literal, or one of `params` named alone (`N`, `{ N }`).
fn length(expr: &syn::Expr, params: &[&Ident]) -> Option<Len> {
    if let Some(n) = int_literal(expr) {
        return Some(Len::Known(n));
    }
    match expr {
        syn::Expr::Path(p) if p.qself.is_none() => {
            param_index(p.path.get_ident()?, params).map(Len::Param)
        }
        syn::Expr::Block(b) if b.block.stmts.len() == 1 => match &b.block.stmts[0] {
            syn::Stmt::Expr(e, None) => length(e, params),
            _ => None,
        },
        syn::Expr::Group(g) => length(&g.expr, params),
        syn::Expr::Paren(p) => length(&p.expr, params),
        _ => None,
    }
}

fn param_index(name: &Ident, params: &[&Ident]) -> Option<usize> {
    params.iter().position(|p| *p == name)
}

/// An array of a state shape whose length is not an integer literal (`[f64; N * N]`,
/// `[Vector3<f64>; SIZE]`, `[[f64; 3]; N]`).
pub(crate) fn array_with_computed_length(ty: &Type) -> bool {
    match ty {
        Type::Paren(p) => array_with_computed_length(&p.elem),
        Type::Group(g) => array_with_computed_length(&g.elem),
        Type::Array(a) => {
            let row = is_f64(&a.elem)
                || matches!(shape_of(&a.elem), Some(Shape::Array(_) | Shape::Vector(_)))
                || array_with_computed_length(&a.elem);
            row && (int_literal(&a.len).is_none() || array_with_computed_length(&a.elem))
        }
        _ => false,
    }
}
