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
            let parts = match self.expr(&field.expr)? {
                Value::Scalar(x) => vec![x],
                Value::Vector(v) => v,
                Value::Tuple(_) => return Err(self.error(&field.expr, "a tuple")),
            };
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
        let flat = |v: Value| match v {
            Value::Scalar(x) => Some(vec![x]),
            Value::Vector(v) => Some(v),
            Value::Tuple(_) => None,
        };
        let mismatch = |l: &Self| {
            l.error(
                &f.sig.output,
                "a return value whose shape does not match the state",
            )
        };
        match self.model.order {
            Order::First => {
                let v = flat(value).ok_or_else(|| mismatch(self))?;
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
                    .map(|f| f.shape.len())
                    .collect();
                let parts = match (value, velocities.len()) {
                    (Value::Tuple(parts), n) if n > 1 => parts,
                    (single, 1) => vec![single],
                    _ => return Err(mismatch(self)),
                };
                let mut accelerations = Vec::new();
                for (part, len) in parts.into_iter().zip(&velocities) {
                    let v = flat(part).ok_or_else(|| mismatch(self))?;
                    if v.len() != *len {
                        return Err(mismatch(self));
                    }
                    accelerations.extend(v);
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
        match shape {
            Shape::Scalar => Value::Scalar(self.graph.var(offset)),
            _ => Value::Vector(
                (0..shape.len())
                    .map(|i| self.graph.var(offset + i))
                    .collect(),
            ),
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

pub(super) fn vector_len(ty: &str) -> Option<usize> {
    ty.strip_prefix("Vector")
        .and_then(|n| n.parse().ok())
        .filter(|n| (1..=6).contains(n))
}
