//! The values after a branch: each local the arms left different, and the branch's own value,
//! selected by the arm taken ([`Chooser`]: a selector the prologue sets, or conditions on the
//! state), part by part.

use syn::Expr;

use super::branches::Chooser;
use super::scope::{Binding, Scopes};
use super::{Lowering, Value};
use crate::ir::ExprId;

impl Lowering<'_> {
    /// Brings the arms' scopes back together: every binding the arms left different is selected
    /// by the arm taken (a local the lowering does not follow is read back by name instead).
    pub(super) fn merge(
        &mut self,
        chooser: &Chooser,
        arms: &[Scopes],
        at: &Expr,
    ) -> syn::Result<()> {
        let names: Vec<(usize, String)> = self
            .scopes
            .iter()
            .enumerate()
            .flat_map(|(level, scope)| scope.keys().map(move |k| (level, k.clone())))
            .collect();
        for (level, name) in names {
            let bindings: Vec<&Binding> = arms.iter().map(|s| &s[level][&name]).collect();
            if bindings.iter().all(|b| *b == bindings[0]) {
                self.scopes[level].insert(name, bindings[0].clone());
                continue;
            }
            // Arms chosen by the state give a local a state-dependent value, whatever each
            // arm's own value.
            let dependent =
                bindings.iter().any(|b| b.dependent) || matches!(chooser, Chooser::Conditions(_));
            let values: Option<Vec<Value>> = bindings.iter().map(|b| b.value.clone()).collect();
            let value = match values {
                Some(values) => Some(self.select(chooser, values, at)?),
                None if dependent => {
                    return Err(self.error(
                        at,
                        format_args!(
                            "a branch that gives `{name}` a state-dependent value in some arms \
                             and one odyn does not follow in others"
                        ),
                    ));
                }
                // Every arm's code odyn does not follow runs, so what such code left in `name`
                // would be the last arm's whichever arm the state takes.
                None if matches!(chooser, Chooser::Conditions(_)) => {
                    return Err(self.error(
                        at,
                        format_args!(
                            "an `if` on the state whose arms change `{name}` by code odyn does \
                             not follow (change it before the `if`, or give it a value in each \
                             arm)"
                        ),
                    ));
                }
                None => None,
            };
            self.scopes[level].insert(name, Binding { value, dependent });
        }
        Ok(())
    }

    /// `if arm 0 was taken { v₀ } else if arm 1 was { v₁ } … else { vₙ }`, part by part.
    pub(super) fn select(
        &mut self,
        chooser: &Chooser,
        values: Vec<Value>,
        at: &Expr,
    ) -> syn::Result<Value> {
        let mut values = values;
        let mut merged = values.pop().expect("a branch has arms");
        while let Some(value) = values.pop() {
            let arm = values.len();
            merged = self.select_pair(chooser, arm, value, merged, at)?;
        }
        Ok(merged)
    }

    fn select_pair(
        &mut self,
        chooser: &Chooser,
        arm: usize,
        then: Value,
        otherwise: Value,
        at: &Expr,
    ) -> syn::Result<Value> {
        match (then, otherwise) {
            (Value::Scalar(a), Value::Scalar(b)) => {
                Ok(Value::Scalar(self.choose(chooser, arm, a, b)))
            }
            (Value::Vector(a), Value::Vector(b)) if a.len() == b.len() => Ok(Value::Vector(
                a.into_iter()
                    .zip(b)
                    .map(|(x, y)| self.choose(chooser, arm, x, y))
                    .collect(),
            )),
            (Value::Rows(a), Value::Rows(b)) if a.len() == b.len() => {
                let mut rows = Vec::with_capacity(a.len());
                for (x, y) in a.into_iter().zip(b) {
                    match self.select_pair(chooser, arm, Value::Vector(x), Value::Vector(y), at)? {
                        Value::Vector(row) => rows.push(row),
                        _ => {
                            return Err(
                                self.error(at, "branch arms whose values have different shapes")
                            );
                        }
                    }
                }
                Ok(Value::Rows(rows))
            }
            (Value::Tuple(a), Value::Tuple(b)) if a.len() == b.len() => Ok(Value::Tuple(
                a.into_iter()
                    .zip(b)
                    .map(|(x, y)| self.select_pair(chooser, arm, x, y, at))
                    .collect::<syn::Result<_>>()?,
            )),
            _ => Err(self.error(at, "branch arms whose values have different shapes")),
        }
    }

    /// `then` if `arm` was taken, else `otherwise`.
    fn choose(&mut self, chooser: &Chooser, arm: usize, then: ExprId, otherwise: ExprId) -> ExprId {
        match chooser {
            Chooser::Selector(selector) => {
                let arm = u32::try_from(arm).expect("fewer than 2³² arms");
                self.graph.select(*selector, arm, then, otherwise)
            }
            Chooser::Conditions(conditions) => self.when(&conditions[arm], then, otherwise),
        }
    }
}
