//! The struct of a fixed-size model: its `#[state]` or `#[position]`/`#[velocity]` fields.

use syn::{Attribute, Fields, ItemStruct};

use crate::errors::Errors;
use crate::model::{
    Model, Order, Role, StateField, array_with_computed_length, const_params, shape_in,
};
use crate::syntax::no_arguments;

/// Reads the model from its struct, reporting every problem to `errors`.
pub(crate) fn parse<'a>(item: &'a ItemStruct, errors: &mut Errors) -> Option<Model<'a>> {
    // Refused before the front-end with its own error (`kinds::expand_struct`).
    let Fields::Named(named) = &item.fields else {
        return None;
    };
    let params = const_params(item);
    let mut declared = Vec::new();
    for field in &named.named {
        let Some(role) = role_of(&field.attrs, errors) else {
            continue;
        };
        let ident = field.ident.as_ref().expect("named fields have names");
        match shape_in(&field.ty, &params) {
            Some(shape) if shape.is_generic() || shape.len() > 0 => {
                declared.push((StateField { ident, role, shape }, field))
            }
            Some(_) => errors.at(&field.ty, "a state field needs at least one component"),
            None if array_with_computed_length(&field.ty) => errors.at(
                &field.ty,
                "the length of a state array must be an integer literal, such as `[f64; 64]` \
                 or `[Vector3<f64>; 5]`, or a const parameter of the model alone \
                 (`[f64; N]` in `struct Chain<const N: usize>`): `#[system]` lays the state out \
                 before constants are evaluated",
            ),
            None => errors.at(
                &field.ty,
                format_args!(
                    "unsupported type for a `#[{}]` field; supported: `f64`, `[f64; N]`, \
                     `SVector<f64, N>`, `Vector1<f64>` … `Vector6<f64>`, and arrays of those \
                     arrays and vectors (`[[f64; M]; N]`, `[Vector3<f64>; N]`)",
                    role.attribute()
                ),
            ),
        }
    }

    let count = |role| declared.iter().filter(|(f, _)| f.role == role).count();
    let (positions, velocities, states) = (
        count(Role::Position),
        count(Role::Velocity),
        count(Role::State) + count(Role::Algebraic),
    );
    if !super::algebraic::fields_accepted(&declared, positions + velocities, &params, errors) {
        return None;
    }
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
        let (first_state, _) = declared
            .iter()
            .find(|(f, _)| matches!(f.role, Role::State | Role::Algebraic))?;
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
        pair_positions_and_velocities(&declared, &params, errors);
    }
    let mut fields: Vec<_> = declared.into_iter().map(|(f, _)| f).collect();
    // Layout: every position, then every velocity (a stable sort keeps declaration order).
    fields.sort_by_key(|f| f.role == Role::Velocity);
    Some(Model {
        item,
        order,
        states: fields,
        params,
    })
}

/// Positions and velocities pair up in declaration order, with equal shapes.
fn pair_positions_and_velocities(
    declared: &[(StateField<'_>, &syn::Field)],
    params: &[&syn::Ident],
    errors: &mut Errors,
) {
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
                    v.0.shape.describe(params),
                    p.0.ident,
                    p.0.shape.describe(params)
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
        no_arguments(
            attr,
            format_args!("`#[{}]` takes no arguments", role.attribute()),
            errors,
        );
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
