//! The state description every model kind hands to lowering: which fields are state, in which
//! role, of which shape — and the shapes of the parameters beside them.

mod shape;

pub(crate) use self::shape::{Len, Shape, array_with_computed_length, shape_in, shape_of};

use proc_macro2::TokenStream;
use quote::quote;
use syn::{Ident, ItemStruct};

/// What a state field is.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Role {
    Position,
    Velocity,
    State,
    /// A component whose row of `derivative` is an algebraic equation 0 = g(t, y, z).
    Algebraic,
}

impl Role {
    pub(crate) const ATTRIBUTES: [(&'static str, Role); 4] = [
        ("position", Role::Position),
        ("velocity", Role::Velocity),
        ("state", Role::State),
        ("algebraic", Role::Algebraic),
    ];

    pub(crate) fn attribute(self) -> &'static str {
        Self::ATTRIBUTES
            .iter()
            .find(|(_, r)| *r == self)
            .map_or("", |(name, _)| name)
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
    /// The struct's const parameters (`N` of `struct Chain<const N: usize>`), in order.
    pub(crate) params: Vec<&'a Ident>,
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
            params: const_params(item),
        }
    }

    /// Whether the struct has const parameters: its code is then emitted as written, never
    /// lowered, and its Jacobian taken by central differences.
    pub(crate) fn is_generic(&self) -> bool {
        !self.params.is_empty()
    }

    /// The state type as generated code names it: `ChainState<N>`, or `SpringState`.
    pub(crate) fn state_type(&self) -> TokenStream {
        let name = self.state_ident();
        let params = &self.params;
        if params.is_empty() {
            quote!(#name)
        } else {
            quote!(#name<#(#params),*>)
        }
    }

    /// The number of components in generated code: `4`, or `(N + N)`.
    pub(crate) fn len_tokens(&self) -> TokenStream {
        if !self.is_generic() {
            let n = proc_macro2::Literal::usize_unsuffixed(self.len());
            return quote!(#n);
        }
        let parts = self.states.iter().map(|f| f.shape.len_tokens(&self.params));
        quote!((0 #(+ #parts)*))
    }

    /// A field's canonical type.
    pub(crate) fn type_of(&self, shape: Shape) -> TokenStream {
        shape.to_type(&self.params)
    }

    /// A field's type as errors show it.
    pub(crate) fn describe(&self, shape: Shape) -> String {
        shape.describe(&self.params)
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

/// The const parameters of a model struct, in order (`N` of `struct Chain<const N: usize>`).
pub(crate) fn const_params(item: &ItemStruct) -> Vec<&Ident> {
    item.generics.const_params().map(|c| &c.ident).collect()
}
