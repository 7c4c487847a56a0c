//! The state in a lowered body: reads of state fields (`self.x`, as a scalar or a vector of
//! graph variables), parameter shapes, the state literal `<Model>State { … }`, and the function's
//! value as f(t, y) in state layout.

use syn::{Ident, Member};

use super::{Lowering, Value};
use crate::ir::ExprId;
use crate::model::{Order, Role, Shape, shape_of};

impl Lowering<'_> {
    /// `<Model>State { x: …, v: … }`, the return value of `derivative`.
    pub(super) fn state_literal(&mut self, s: &syn::ExprStruct) -> syn::Result<Value> {
        if !s.path.is_ident(&self.model.state_ident()) {
            return Err(self.error(&s.path, "a struct literal other than the model's state"));
        }
        if let Some(rest) = &s.rest {
            return Err(self.error(rest, "`..` in the state literal"));
        }
        let mut components = vec![None; self.model.len()];
        for field in &s.fields {
            let Member::Named(name) = &field.member else {
                return Err(self.error(field, "a tuple field"));
            };
            let offset = self
                .offset(name)
                .ok_or_else(|| self.error(name, "an unknown state field"))?;
            let shape = self.model.field(name).expect("offset found it").shape;
            let parts = components_of(self.expr(&field.expr)?, shape).ok_or_else(|| {
                self.error(&field.expr, "a value whose shape does not match its field")
            })?;
            for (i, part) in parts.into_iter().enumerate() {
                components[offset + i] = Some(part);
            }
        }
        let components: Option<Vec<_>> = components.into_iter().collect();
        components
            .map(Value::Vector)
            .ok_or_else(|| self.error(s, "a state literal with missing fields"))
    }

    /// f(t, y) in state layout order, from the body's value.
    pub(super) fn outputs(
        &mut self,
        value: Value,
        f: &syn::ImplItemFn,
    ) -> syn::Result<Vec<ExprId>> {
        let mismatch = |l: &Self| {
            l.error(
                &f.sig.output,
                "a return value whose shape does not match the state",
            )
        };
        match self.model.order {
            Order::First => {
                // The state literal's value (already in layout), or the one number of a scalar
                // state.
                let v = match value {
                    Value::Scalar(x) => vec![x],
                    Value::Vector(v) => v,
                    Value::Tuple(_) | Value::Rows(_) => return Err(mismatch(self)),
                };
                if v.len() == self.model.len() {
                    Ok(v)
                } else {
                    Err(mismatch(self))
                }
            }
            Order::Second => {
                let velocities: Vec<_> = self
                    .model
                    .with_role(Role::Velocity)
                    .map(|f| f.shape)
                    .collect();
                let parts = match (value, velocities.len()) {
                    (Value::Tuple(parts), n) if n > 1 => parts,
                    (single, 1) => vec![single],
                    _ => return Err(mismatch(self)),
                };
                let mut accelerations = Vec::new();
                if parts.len() != velocities.len() {
                    return Err(mismatch(self));
                }
                for (part, shape) in parts.into_iter().zip(velocities) {
                    accelerations.extend(components_of(part, shape).ok_or_else(|| mismatch(self))?);
                }
                // y = [q; v], so f = [v; a].
                let dof = accelerations.len();
                let mut f: Vec<_> = (0..dof).map(|i| self.graph.var(dof + i)).collect();
                f.extend(accelerations);
                Ok(f)
            }
        }
    }

    pub(super) fn offset(&self, name: &Ident) -> Option<usize> {
        let mut offset = 0;
        for f in &self.model.states {
            if f.ident == name {
                return Some(offset);
            }
            offset += f.shape.len();
        }
        None
    }

    pub(super) fn state_value(&mut self, offset: usize, shape: Shape) -> Value {
        self.shaped(shape, |l, i| l.graph.var(offset + i))
    }

    /// A value of `shape` whose component `i` (in layout order) is `component(i)`: a number, a
    /// vector, or rows as a tuple of vectors.
    pub(super) fn shaped(
        &mut self,
        shape: Shape,
        mut component: impl FnMut(&mut Self, usize) -> ExprId,
    ) -> Value {
        match shape {
            Shape::Scalar => Value::Scalar(component(self, 0)),
            Shape::Array(n) | Shape::Vector(n) => {
                Value::Vector((0..n.count()).map(|i| component(self, i)).collect())
            }
            Shape::Rows(n, row) => {
                let m = row.len();
                Value::Rows(
                    (0..n.count())
                        .map(|i| (0..m).map(|j| component(self, m * i + j)).collect())
                        .collect(),
                )
            }
        }
    }

    pub(super) fn parameter_shape(&self, name: &Ident) -> Option<Shape> {
        let syn::Fields::Named(fields) = &self.model.item.fields else {
            return None;
        };
        fields
            .named
            .iter()
            .find(|f| f.ident.as_ref() == Some(name))
            .and_then(|f| shape_of(&f.ty))
    }
}

/// The components of `value`, in layout order, if it has the shape `shape`.
fn components_of(value: Value, shape: Shape) -> Option<Vec<ExprId>> {
    match (value, shape) {
        (Value::Scalar(x), Shape::Scalar) => Some(vec![x]),
        (Value::Vector(v), Shape::Array(n) | Shape::Vector(n)) if v.len() == n.count() => Some(v),
        (Value::Rows(rows), Shape::Rows(n, row))
            if rows.len() == n.count() && rows.iter().all(|r| r.len() == row.len()) =>
        {
            Some(rows.concat())
        }
        _ => None,
    }
}

pub(super) fn vector_len(ty: &str) -> Option<usize> {
    ty.strip_prefix("Vector")
        .and_then(|n| n.parse().ok())
        .filter(|n| (1..=6).contains(n))
}
