//! Stage 2: the model struct — which fields are state, in which role, of which shape.

use proc_macro2::TokenStream;
use quote::quote;
use syn::{Attribute, Expr, Fields, GenericArgument, Ident, ItemStruct, Lit, PathArguments, Type};

use crate::errors::Errors;

/// What a state field is.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Role {
    Position,
    Velocity,
    State,
}

impl Role {
    const ATTRIBUTES: [(&'static str, Role); 3] = [
        ("position", Role::Position),
        ("velocity", Role::Velocity),
        ("state", Role::State),
    ];

    fn attribute(self) -> &'static str {
        Self::ATTRIBUTES
            .iter()
            .find(|(_, r)| *r == self)
            .map_or("", |(name, _)| name)
    }
}

/// The shape of a state field's value.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Shape {
    /// `f64`
    Scalar,
    /// `[f64; N]`
    Array(usize),
    /// `SVector<f64, N>` or `VectorN<f64>`
    Vector(usize),
}

impl Shape {
    /// Number of `f64` components.
    pub(crate) fn len(self) -> usize {
        match self {
            Shape::Scalar => 1,
            Shape::Array(n) | Shape::Vector(n) => n,
        }
    }

    /// The canonical type, with absolute paths.
    pub(crate) fn to_type(self) -> TokenStream {
        let n = proc_macro2::Literal::usize_unsuffixed(self.len());
        match self {
            Shape::Scalar => quote!(f64),
            Shape::Array(_) => quote!([f64; #n]),
            Shape::Vector(_) => quote!(::odyn::__private::nalgebra::SVector<f64, #n>),
        }
    }

    pub(crate) fn describe(self) -> String {
        match self {
            Shape::Scalar => "f64".to_owned(),
            Shape::Array(n) => format!("[f64; {n}]"),
            Shape::Vector(n) => format!("SVector<f64, {n}>"),
        }
    }
}

/// One state field.
pub(crate) struct StateField<'a> {
    pub(crate) ident: &'a Ident,
    pub(crate) role: Role,
    pub(crate) shape: Shape,
}

/// First-order (`#[state]`) or second-order (`#[position]`/`#[velocity]`).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Order {
    First,
    Second,
}

/// The model: the user's struct and its state fields in state layout order (every position,
/// then every velocity; or the `#[state]` fields in declaration order).
pub(crate) struct Model<'a> {
    pub(crate) item: &'a ItemStruct,
    pub(crate) order: Order,
    pub(crate) states: Vec<StateField<'a>>,
}

impl Model<'_> {
    pub(crate) fn ident(&self) -> &Ident {
        &self.item.ident
    }

    pub(crate) fn state_ident(&self) -> Ident {
        quote::format_ident!("{}State", self.item.ident)
    }

    pub(crate) fn field(&self, name: &Ident) -> Option<&StateField<'_>> {
        self.states.iter().find(|f| f.ident == name)
    }

    pub(crate) fn with_role(&self, role: Role) -> impl Iterator<Item = &StateField<'_>> {
        self.states.iter().filter(move |f| f.role == role)
    }

    /// Number of `f64` components of the state.
    pub(crate) fn len(&self) -> usize {
        self.states.iter().map(|f| f.shape.len()).sum()
    }
}

/// Reads the model from its struct, reporting every problem to `errors`.
pub(crate) fn parse<'a>(item: &'a ItemStruct, errors: &mut Errors) -> Option<Model<'a>> {
    if !item.generics.params.is_empty() || item.generics.where_clause.is_some() {
        errors.at(
            &item.generics,
            "generic models are not supported; use concrete `f64` fields",
        );
    }
    let Fields::Named(named) = &item.fields else {
        errors.at_span(
            item.ident.span(),
            "a model must be a struct with named fields, such as `struct Spring { x: f64, .. }`",
        );
        return None;
    };
    let mut declared = Vec::new();
    for field in &named.named {
        let Some(role) = role_of(&field.attrs, errors) else {
            continue;
        };
        let ident = field.ident.as_ref().expect("named fields have names");
        match shape_of(&field.ty) {
            Some(shape) if shape.len() > 0 => {
                declared.push((StateField { ident, role, shape }, field))
            }
            Some(_) => errors.at(&field.ty, "a state field needs at least one component"),
            None if array_of_f64_with_computed_length(&field.ty) => errors.at(
                &field.ty,
                "the length of a state array must be an integer literal, such as `[f64; 64]`: \
                 `#[system]` lays the state out before constants are evaluated, so write the \
                 length out",
            ),
            None => errors.at(
                &field.ty,
                format_args!(
                    "unsupported type for a `#[{}]` field; supported: `f64`, `[f64; N]`, \
                     `SVector<f64, N>`, `Vector1<f64>` … `Vector6<f64>`",
                    role.attribute()
                ),
            ),
        }
    }

    let count = |role| declared.iter().filter(|(f, _)| f.role == role).count();
    let (positions, velocities, states) = (
        count(Role::Position),
        count(Role::Velocity),
        count(Role::State),
    );
    if declared.is_empty() {
        if errors.is_empty() {
            errors.at_span(
                item.ident.span(),
                format_args!(
                    "model `{}` has no state; mark fields `#[position]` and `#[velocity]` \
                     (second-order) or `#[state]` (first-order)",
                    item.ident
                ),
            );
        }
        return None;
    }
    if states > 0 && positions + velocities > 0 {
        let (first_state, _) = declared.iter().find(|(f, _)| f.role == Role::State)?;
        errors.at(
            first_state.ident,
            "`#[state]` cannot be mixed with `#[position]`/`#[velocity]`; a model is either \
             first-order or second-order",
        );
        return None;
    }
    let order = if states > 0 {
        Order::First
    } else {
        Order::Second
    };
    if order == Order::Second {
        pair_positions_and_velocities(&declared, errors);
    }
    let mut fields: Vec<_> = declared.into_iter().map(|(f, _)| f).collect();
    // Layout: every position, then every velocity (a stable sort keeps declaration order).
    fields.sort_by_key(|f| f.role == Role::Velocity);
    Some(Model {
        item,
        order,
        states: fields,
    })
}

/// Positions and velocities pair up in declaration order, with equal shapes.
fn pair_positions_and_velocities(declared: &[(StateField<'_>, &syn::Field)], errors: &mut Errors) {
    let positions: Vec<_> = declared
        .iter()
        .filter(|(f, _)| f.role == Role::Position)
        .collect();
    let velocities: Vec<_> = declared
        .iter()
        .filter(|(f, _)| f.role == Role::Velocity)
        .collect();
    for (p, v) in positions.iter().zip(&velocities) {
        if p.0.shape != v.0.shape {
            errors.at(
                &v.1.ty,
                format_args!(
                    "velocity `{}` is `{}` but its position `{}` is `{}`; a position and its \
                     velocity have the same shape",
                    v.0.ident,
                    v.0.shape.describe(),
                    p.0.ident,
                    p.0.shape.describe()
                ),
            );
        }
    }
    for (p, _) in positions.iter().skip(velocities.len()) {
        errors.at(
            p.ident,
            format_args!(
                "`#[position]` field `{}` has no `#[velocity]` field to pair with; positions and \
                 velocities pair up in declaration order",
                p.ident
            ),
        );
    }
    for (v, _) in velocities.iter().skip(positions.len()) {
        errors.at(
            v.ident,
            format_args!(
                "`#[velocity]` field `{}` has no `#[position]` field to pair with; positions and \
                 velocities pair up in declaration order",
                v.ident
            ),
        );
    }
}

/// The role a field's attributes give it, if any.
fn role_of(attrs: &[Attribute], errors: &mut Errors) -> Option<Role> {
    let mut found: Option<(Role, &Attribute)> = None;
    for attr in attrs {
        let Some((_, role)) = Role::ATTRIBUTES
            .iter()
            .find(|(name, _)| attr.path().is_ident(name))
        else {
            continue;
        };
        if let Err(e) = attr.meta.require_path_only() {
            errors.push(syn::Error::new(
                e.span(),
                format_args!("`#[{}]` takes no arguments", role.attribute()),
            ));
        }
        match found {
            Some((first, _)) => errors.at(
                attr,
                format_args!(
                    "a field has one role, but this one is already `#[{}]`",
                    first.attribute()
                ),
            ),
            None => found = Some((*role, attr)),
        }
    }
    found.map(|(role, _)| role)
}

/// The shape of a supported state type.
pub(crate) fn shape_of(ty: &Type) -> Option<Shape> {
    match ty {
        Type::Paren(p) => shape_of(&p.elem),
        Type::Group(g) => shape_of(&g.elem),
        Type::Array(a) if is_f64(&a.elem) => int_literal(&a.len).map(Shape::Array),
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
                    int_literal(n).map(Shape::Vector)
                }
                (vector, [GenericArgument::Type(t)]) if is_f64(t) => vector
                    .strip_prefix("Vector")
                    .and_then(|n| n.parse::<usize>().ok())
                    .filter(|n| (1..=6).contains(n))
                    .map(Shape::Vector),
                _ => None,
            }
        }
        _ => None,
    }
}

/// `[f64; N]` whose length is not an integer literal (`[f64; N * N]`, `[f64; SIZE]`).
fn array_of_f64_with_computed_length(ty: &Type) -> bool {
    matches!(ty, Type::Array(a) if is_f64(&a.elem) && int_literal(&a.len).is_none())
}

/// Whether `ty` is plain `f64`.
pub(crate) fn is_f64(ty: &Type) -> bool {
    matches!(ty, Type::Path(p) if p.qself.is_none() && p.path.is_ident("f64"))
}

/// The value of an integer literal, looking through parentheses and invisible groups.
pub(crate) fn int_literal(expr: &Expr) -> Option<usize> {
    match expr {
        Expr::Lit(syn::ExprLit {
            lit: Lit::Int(i), ..
        }) => i.base10_parse().ok(),
        Expr::Group(g) => int_literal(&g.expr),
        Expr::Paren(p) => int_literal(&p.expr),
        _ => None,
    }
}

/// The struct as the user wrote it, minus the role attributes (which are odyn's, not rustc's).
pub(crate) fn strip_roles(item: &ItemStruct) -> ItemStruct {
    let mut item = item.clone();
    if let Fields::Named(named) = &mut item.fields {
        for field in &mut named.named {
            field.attrs.retain(|a| {
                !Role::ATTRIBUTES
                    .iter()
                    .any(|(name, _)| a.path().is_ident(name))
            });
        }
    }
    item
}
