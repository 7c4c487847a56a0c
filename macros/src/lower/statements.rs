//! Statements: `let` (with tuple and slice patterns), assignments and state-free statements;
//! branches on parameters are lowered in [`super::branches`].
//!
//! A branch on parameters becomes a [`super::Branch`] of the prologue (the same branch runs before the
//! Jacobian and records which arm it took) and `Select` nodes in the graph: every local an arm
//! changes, and the value of a branch expression, is selected by that record, so each control path
//! is differentiated. A branch with a `return` in it is lowered with the statements after it
//! appended to every arm that does not return — `if c { return a; } rest` is `if c { a } else
//! { rest }` — so the function's value is selected the same way.

use std::collections::HashMap;

use quote::ToTokens;
use syn::{Block, Expr, Local, Stmt};

use super::names::returns;
use super::scope::{Binding, assigned};
use super::{Lowering, Prologue, Value};

/// Where a list of statements sits.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum Context {
    /// The function's own statements (or an arm of a branch among them, with the rest of the
    /// function appended): may `return`; a final expression is the function's value.
    Function,
    /// An arm of a branch used as a statement: no value; `return` only when the branch is among
    /// the function's own statements (handled before the arm is reached).
    Arm,
    /// A block used as a value (`let a = { … };`, an arm of a branch expression): ends with its
    /// value; no `return`.
    Block,
}

/// How a list of statements ends.
pub(super) enum Ending {
    /// With a value: the block's, or the function's.
    Value(Value),
    /// Without one (an arm of a branch statement).
    Continue,
}

impl Lowering<'_> {
    /// The function's body: its value.
    pub(super) fn body(&mut self, block: &Block) -> syn::Result<Value> {
        self.scopes.push(HashMap::new());
        let ending = self.run(&block.stmts, Context::Function);
        self.scopes.pop();
        match ending? {
            Ending::Value(value) => Ok(value),
            Ending::Continue => Err(self.error(block, "a body that does not end in an expression")),
        }
    }

    /// A block used as a value.
    pub(super) fn block_value(&mut self, block: &Block) -> syn::Result<Value> {
        self.scopes.push(HashMap::new());
        let ending = self.run(&block.stmts, Context::Block);
        self.scopes.pop();
        match ending? {
            Ending::Value(value) => Ok(value),
            Ending::Continue => Err(self.error(block, "a block that does not end in a value")),
        }
    }

    pub(super) fn run(&mut self, stmts: &[Stmt], context: Context) -> syn::Result<Ending> {
        for (i, stmt) in stmts.iter().enumerate() {
            if let Stmt::Expr(Expr::Return(r), _) = stmt {
                if context != Context::Function {
                    return Err(self.refuse(
                        r,
                        "a `return` inside a branch odyn cannot follow: a `return` may leave the \
                         function only from its own statements or from an `if`/`match` among \
                         them",
                    ));
                }
                let value = r
                    .expr
                    .as_ref()
                    .ok_or_else(|| self.refuse(r, "a `return` without a value"))?;
                return Ok(Ending::Value(self.expr(value)?));
            }
            if context == Context::Function
                && let Stmt::Expr(branch @ (Expr::If(_) | Expr::Match(_)), _) = stmt
                && returns(std::slice::from_ref(stmt))
            {
                return self
                    .branch_returning(branch, &stmts[i + 1..])
                    .map(Ending::Value);
            }
            if i + 1 == stmts.len()
                && context != Context::Arm
                && let Stmt::Expr(e, None) = stmt
            {
                return Ok(Ending::Value(self.expr(e)?));
            }
            self.statement(stmt)?;
        }
        Ok(Ending::Continue)
    }

    fn statement(&mut self, stmt: &Stmt) -> syn::Result<()> {
        match stmt {
            Stmt::Local(local) => self.local(stmt, local),
            Stmt::Expr(Expr::Assign(assign), _) => {
                let dependent = self.depends(&assign.right);
                let value = self.expr(&assign.right)?;
                self.assign(stmt, &assign.left, |_, _| Ok(value), dependent)
            }
            Stmt::Expr(Expr::Binary(b), _) if super::compound(&b.op).is_some() => {
                let op = super::compound(&b.op).expect("checked by the guard");
                let dependent = self.depends(&b.right);
                let rhs = self.expr(&b.right)?;
                let at = b.op.to_token_stream();
                self.assign(
                    stmt,
                    &b.left,
                    |l, old| l.arithmetic(&at, op, old, rhs),
                    dependent,
                )
            }
            Stmt::Item(_) => {
                self.prologue.push(Prologue::Stmt(Box::new(stmt.clone())));
                Ok(())
            }
            Stmt::Expr(e @ (Expr::If(_) | Expr::Match(_)), _) => self.branch_statement(e),
            Stmt::Expr(e, _) if returns(std::slice::from_ref(stmt)) => Err(self.refuse(
                e,
                "a `return` inside a loop or block odyn cannot follow; return from the \
                 function's own statements or from an `if`/`match` among them",
            )),
            Stmt::Expr(e, _) if !self.depends(e) => {
                self.state_free(stmt, e);
                Ok(())
            }
            Stmt::Macro(m) if !self.depends_tokens(&m.mac.tokens) => Ok(()),
            Stmt::Expr(Expr::ForLoop(l), _) if self.depends(&l.expr) => {
                Err(self.error(&l.expr, "the state in a loop bound (`for`)"))
            }
            Stmt::Expr(Expr::ForLoop(l), _) if l.label.is_none() => self.unroll_for(l),
            Stmt::Expr(Expr::While(w), _) if self.depends(&w.cond) => {
                Err(self.error(&w.cond, "the state in a loop condition (`while`)"))
            }
            Stmt::Expr(Expr::While(w), _) if w.label.is_none() => self.unroll_while(w),
            Stmt::Expr(Expr::ForLoop(l), _) => Err(self.error(
                l.for_token,
                "a labelled loop whose body reads the state (`for`)",
            )),
            Stmt::Expr(Expr::While(w), _) => Err(self.error(
                w.while_token,
                "a labelled loop whose body reads the state (`while`)",
            )),
            Stmt::Expr(Expr::Loop(l), _) => {
                Err(self.error(l.loop_token, "a loop that reads the state (`loop`)"))
            }
            other => Err(self.error(
                other,
                "a statement other than `let`, an assignment to a local, or a branch on \
                 parameters",
            )),
        }
    }

    /// `let pattern = value;`
    fn local(&mut self, stmt: &Stmt, local: &Local) -> syn::Result<()> {
        let init = local
            .init
            .as_ref()
            .ok_or_else(|| self.error(local, "a `let` without a value"))?;
        if let Some((_, diverge)) = &init.diverge {
            return Err(self.error(diverge, "`let … else`"));
        }
        let dependent = self.depends(&init.expr);
        let value = self.expr(&init.expr)?;
        if !dependent {
            self.prologue.push(Prologue::Stmt(Box::new(stmt.clone())));
        }
        if !self.bind_pattern(&local.pat, value, dependent) {
            if dependent {
                return Err(self.error(
                    &local.pat,
                    "a `let` pattern that does not fit its value (a tuple of another length, \
                     or a pattern other than names, tuples, slices and `_`)",
                ));
            }
            // A state-free value the pattern takes apart in ways odyn does not follow: its names
            // stay the user's locals, read by name in the prologue.
            self.bind_unfollowed(&local.pat);
        }
        Ok(())
    }

    /// `target = …` or `target op= …`, where the target is a local or a component of one
    /// (`v[0]`, `v.x`, `pair.1`).
    fn assign(
        &mut self,
        stmt: &Stmt,
        target: &Expr,
        update: impl FnOnce(&mut Self, Value) -> syn::Result<Value>,
        rhs_dependent: bool,
    ) -> syn::Result<()> {
        // `a[i][j].x = …`: the local `a` and the components named on the way, outermost first.
        let mut base = target;
        let mut path = Vec::new();
        loop {
            match base {
                Expr::Index(index) => {
                    path.push(self.known_index(&index.index).ok_or_else(|| {
                        self.error(
                            &index.index,
                            "an index that is not an integer literal (or a loop variable of an \
                             unrolled loop)",
                        )
                    }));
                    base = &index.expr;
                }
                Expr::Field(field) => {
                    path.push(super::expr::component_index(field).ok_or_else(|| {
                        self.error(&field.member, "a field other than `x`, `y`, `z`, `w`")
                    }));
                    base = &field.base;
                }
                _ => break,
            }
        }
        path.reverse();
        let Some(name) = super::names::path_name(base) else {
            return Err(self.error(target, "assigning to something other than a local"));
        };
        let Some(old) = self.lookup(&name).cloned() else {
            return Err(self.error(
                target,
                format_args!("assigning to `{name}`, which is not a local"),
            ));
        };
        let dependent = old.dependent || rhs_dependent;
        // Whether odyn follows the target: a local it has a value for, and the component of a
        // vector or tuple named by a literal.
        let followed = old.value.as_ref().is_some_and(|v| {
            path.iter().all(Result::is_ok) && (path.is_empty() || !matches!(v, Value::Scalar(_)))
        });
        if !dependent && !followed {
            // State-free code odyn does not follow: it runs in the prologue, and the local is the
            // user's from then on, read by name.
            self.prologue.push(Prologue::Stmt(Box::new(stmt.clone())));
            self.rebind(
                &name,
                Binding {
                    value: None,
                    dependent: false,
                },
            );
            return Ok(());
        }
        let Some(old_value) = old.value else {
            return Err(self.error(
                target,
                format_args!(
                    "assigning a state-dependent value to `{name}`, a local bound by a pattern \
                     odyn does not follow"
                ),
            ));
        };
        let path = path.into_iter().collect::<syn::Result<Vec<_>>>()?;
        if let (Value::Scalar(_), Some(&i)) = (&old_value, path.first()) {
            return Err(self.component_of_a_number(target, &name, i));
        }
        let value = self.replace_at(old_value, &path, target, update)?;
        if !dependent {
            self.prologue.push(Prologue::Stmt(Box::new(stmt.clone())));
        }
        self.rebind(
            &name,
            Binding {
                value: Some(value),
                dependent,
            },
        );
        Ok(())
    }

    /// `whole` with its component at `path` (outermost first) replaced by `update` of it.
    fn replace_at<F>(
        &mut self,
        whole: Value,
        path: &[usize],
        target: &Expr,
        update: F,
    ) -> syn::Result<Value>
    where
        F: FnOnce(&mut Self, Value) -> syn::Result<Value>,
    {
        let Some((&i, rest)) = path.split_first() else {
            return update(self, whole);
        };
        let part = self.component(&whole, i, target)?;
        let new = self.replace_at(part, rest, target, update)?;
        let len = match &whole {
            Value::Vector(v) => v.len(),
            Value::Tuple(t) => t.len(),
            Value::Rows(r) => r.len(),
            Value::Scalar(_) => 0,
        };
        if i >= len {
            // Past the end in an arm of a loop bounded at run time that cannot be taken (see
            // `Lowering::component`): nothing to change.
            return Ok(whole);
        }
        match (whole, new) {
            (Value::Rows(mut r), Value::Vector(row)) => {
                r[i] = row;
                Ok(Value::Rows(r))
            }
            (Value::Vector(mut v), Value::Scalar(x)) => {
                v[i] = x;
                Ok(Value::Vector(v))
            }
            (Value::Tuple(mut t), new) => {
                t[i] = new;
                Ok(Value::Tuple(t))
            }
            _ => Err(self.error(target, "a component of another shape")),
        }
    }

    /// The error for `name[i] = …` (or `name.x = …`) of a state-dependent value when odyn reads
    /// `name` as one number: its `let` gave a value odyn did not see into.
    fn component_of_a_number(&self, target: &Expr, name: &str, i: usize) -> syn::Error {
        let part = match target {
            Expr::Field(field) => format!("{name}.{}", field.member.to_token_stream()),
            _ => format!("{name}[{i}]"),
        };
        syn::Error::new_spanned(
            target,
            format!(
                "`{part} = …` in {} sets one component of `{name}`, but odyn reads `{name}` as \
                 one number: its value came from code odyn does not look into (a call, or an \
                 array whose length is not an integer literal); start `{name}` from components \
                 odyn can see, such as `[0.0; 3]`, `[0.0, 0.0, 0.0]` or `Vector3::zeros()`, or \
                 build it whole from its components: `let {name} = [a, b, c];`",
                self.place()
            ),
        )
    }

    /// A statement that does not read the state (a loop over parameters, a call): it runs in the
    /// prologue, and the locals it may change are read back from there afterwards.
    fn state_free(&mut self, stmt: &Stmt, e: &Expr) {
        let names = assigned(self, e);
        if names.is_empty() {
            return;
        }
        self.prologue.push(Prologue::Stmt(Box::new(stmt.clone())));
        if self.reads_time(e) {
            self.time_opaque = true;
        }
        for ident in names {
            let name = ident.to_string();
            let Some(Binding {
                value: Some(value), ..
            }) = self.lookup(&name).cloned()
            else {
                continue;
            };
            let value = self.read_back(ident.into_token_stream(), &value);
            self.rebind(
                &name,
                Binding {
                    value: Some(value),
                    dependent: false,
                },
            );
        }
    }
}
