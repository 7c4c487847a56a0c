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
    /// `[[f64; M]; N]` or `[SVector<f64, M>; N]` (`[Vector3<f64>; N]`): `N` rows of `M`, laid out
    /// row after row.
    Rows(usize, Row),
}

/// One row of a [`Shape::Rows`].
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Row {
    /// `[f64; M]`
    Array(usize),
    /// `SVector<f64, M>` or `VectorM<f64>`
    Vector(usize),
}

impl Row {
    pub(crate) fn len(self) -> usize {
        match self {
            Row::Array(m) | Row::Vector(m) => m,
        }
    }

    fn shape(self) -> Shape {
        match self {
            Row::Array(m) => Shape::Array(m),
            Row::Vector(m) => Shape::Vector(m),
        }
    }
}

impl Shape {
    /// Number of `f64` components.
    pub(crate) fn len(self) -> usize {
        match self {
            Shape::Scalar => 1,
            Shape::Array(n) | Shape::Vector(n) => n,
            Shape::Rows(n, row) => n * row.len(),
        }
    }

    /// The canonical type, with absolute paths.
    pub(crate) fn to_type(self) -> TokenStream {
        let n = proc_macro2::Literal::usize_unsuffixed(self.len());
        match self {
            Shape::Scalar => quote!(f64),
            Shape::Array(_) => quote!([f64; #n]),
            Shape::Vector(_) => quote!(::odyn::__private::nalgebra::SVector<f64, #n>),
            Shape::Rows(rows, row) => {
                let (rows, row) = (proc_macro2::Literal::usize_unsuffixed(rows), row.shape());
                let row = row.to_type();
                quote!([#row; #rows])
            }
        }
    }

    pub(crate) fn describe(self) -> String {
        match self {
            Shape::Scalar => "f64".to_owned(),
            Shape::Array(n) => format!("[f64; {n}]"),
            Shape::Vector(n) => format!("SVector<f64, {n}>"),
            Shape::Rows(n, row) => format!("[{}; {n}]", row.shape().describe()),
        }
    }

    /// The component names of a field `name` of this shape, in layout order: `x`, `x[2]`,
    /// `x[2][1]`.
    pub(crate) fn component_names(self, name: &str) -> Vec<String> {
        match self {
            Shape::Scalar => vec![name.to_owned()],
            Shape::Array(n) | Shape::Vector(n) => (0..n).map(|i| format!("{name}[{i}]")).collect(),
            Shape::Rows(n, row) => (0..n)
                .flat_map(|i| (0..row.len()).map(move |j| format!("{name}[{i}][{j}]")))
                .collect(),
        }
    }

    /// How each component of a value `base` of this shape is read, in layout order: `base`,
    /// `base[2]`, `base[2][1]`.
    pub(crate) fn component_reads(self, base: &TokenStream) -> Vec<TokenStream> {
        match self {
            Shape::Scalar => vec![base.clone()],
            Shape::Array(n) | Shape::Vector(n) => (0..n).map(|i| quote!(#base[#i])).collect(),
            Shape::Rows(n, row) => (0..n)
                .flat_map(|i| (0..row.len()).map(move |j| quote!(#base[#i][#j])))
                .collect(),
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
        Type::Array(a) => {
            let row = match shape_of(&a.elem)? {
                Shape::Array(m) => Row::Array(m),
                Shape::Vector(m) => Row::Vector(m),
                Shape::Scalar | Shape::Rows(..) => return None,
            };
            int_literal(&a.len).map(|n| Shape::Rows(n, row))
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
