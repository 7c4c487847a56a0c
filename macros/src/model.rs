//! The state description every model kind hands to lowering: which fields are state, in which
//! role, of which shape — and the shapes of the parameters beside them.

use proc_macro2::TokenStream;
use quote::quote;
use syn::{GenericArgument, Ident, ItemStruct, PathArguments, Type};

use crate::syntax::{int_literal, is_f64};

/// What a state field is.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Role {
    Position,
    Velocity,
    State,
}

impl Role {
    pub(crate) const ATTRIBUTES: [(&'static str, Role); 3] = [
        ("position", Role::Position),
        ("velocity", Role::Velocity),
        ("state", Role::State),
    ];

    pub(crate) fn attribute(self) -> &'static str {
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
        state_ident(&self.item.ident)
    }

    /// The model as a kernel's lowering sees it: every field a parameter, the state coming in
    /// through the kernel's arguments (particle and grid kernels).
    pub(crate) fn parameters(item: &ItemStruct, order: Order) -> Model<'_> {
        Model {
            item,
            order,
            states: Vec::new(),
        }
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

/// The name of the state type `#[system]` generates for model `model`: `<Model>State`.
pub(crate) fn state_ident(model: &Ident) -> Ident {
    quote::format_ident!("{}State", model)
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
pub(crate) fn array_of_f64_with_computed_length(ty: &Type) -> bool {
    matches!(ty, Type::Array(a) if is_f64(&a.elem) && int_literal(&a.len).is_none())
}
