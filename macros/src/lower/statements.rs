//! Statements: `let` (with tuple and slice patterns), assignments, state-free statements, and
//! branches on parameters — `if`/`match` whose conditions do not read the state — with early
//! `return`s from them.
//!
//! A branch on parameters becomes a [`Branch`] of the prologue (the same branch runs before the
//! Jacobian and records which arm it took) and `Select` nodes in the graph: every local an arm
//! changes, and the value of a branch expression, is selected by that record, so each control path
//! is differentiated. A branch with a `return` in it is lowered with the statements after it
//! appended to every arm that does not return — `if c { return a; } rest` is `if c { a } else
//! { rest }` — so the function's value is selected the same way.

use std::collections::HashMap;

use quote::ToTokens;
use syn::{Block, Expr, ExprIf, ExprMatch, Local, Stmt};

use super::scope::{Binding, assigned, pattern_names, returns};
use super::{Branch, BranchKind, Lowering, Prologue, Value};

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

/// The arms of a branch as statement lists, with the names each arm's pattern binds.
struct Arms {
    kind: BranchKind,
    bodies: Vec<(Vec<Stmt>, Vec<String>)>,
}

type Scopes = Vec<HashMap<String, Binding>>;

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
            Stmt::Expr(Expr::Binary(b), _) if super::expr::compound(&b.op).is_some() => {
                let op = super::expr::compound(&b.op).expect("checked by the guard");
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
            Stmt::Expr(Expr::ForLoop(l), _) => {
                Err(self.error(l.for_token, "a loop whose body reads the state (`for`)"))
            }
            Stmt::Expr(Expr::While(w), _) => {
                Err(self.error(&w.cond, "a loop that reads the state (`while`)"))
            }
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
        let (base, component) = match target {
            Expr::Index(index) => (
                &*index.expr,
                Some(crate::model::int_literal(&index.index).ok_or_else(|| {
                    self.error(&index.index, "an index that is not an integer literal")
                })?),
            ),
            Expr::Field(field) => (
                &*field.base,
                Some(super::expr::component_index(field).ok_or_else(|| {
                    self.error(&field.member, "a field other than `x`, `y`, `z`, `w`")
                })?),
            ),
            other => (other, None),
        };
        let Some(name) = super::scope::path_name(base) else {
            return Err(self.error(target, "assigning to something other than a local"));
        };
        let Some(old) = self.lookup(&name).cloned() else {
            return Err(self.error(
                target,
                format_args!("assigning to `{name}`, which is not a local"),
            ));
        };
        let dependent = old.dependent || rhs_dependent;
        let Some(old_value) = old.value else {
            if dependent {
                return Err(self.error(
                    target,
                    format_args!(
                        "assigning a state-dependent value to `{name}`, a local bound by a \
                         pattern odyn does not follow"
                    ),
                ));
            }
            self.prologue.push(Prologue::Stmt(Box::new(stmt.clone())));
            return Ok(());
        };
        let value = match component {
            None => update(self, old_value)?,
            Some(i) => {
                let part = self.component(&old_value, i, target)?;
                let new = update(self, part)?;
                match (old_value, new) {
                    (Value::Vector(mut v), Value::Scalar(x)) => {
                        v[i] = x;
                        Value::Vector(v)
                    }
                    (Value::Tuple(mut t), new) => {
                        t[i] = new;
                        Value::Tuple(t)
                    }
                    _ => return Err(self.error(target, "a component of another shape")),
                }
            }
        };
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

    // ----- branches ---------------------------------------------------------------------------

    /// The arms of `if`/`match` `e`; its conditions, scrutinee and guards must not read the
    /// state.
    fn arms(&self, e: &Expr) -> syn::Result<Arms> {
        match e {
            Expr::If(i) => self.if_arms(i),
            Expr::Match(m) => self.match_arms(m),
            other => Err(self.error(other, "this kind of branch")),
        }
    }

    fn if_arms(&self, mut branch: &ExprIf) -> syn::Result<Arms> {
        let (mut conditions, mut bodies) = (Vec::new(), Vec::new());
        loop {
            if self.depends(&branch.cond) {
                return Err(self.error(&branch.cond, "branching on the state (`if`)"));
            }
            bodies.push((branch.then_branch.stmts.clone(), let_names(&branch.cond)));
            conditions.push((*branch.cond).clone());
            match branch.else_branch.as_ref().map(|(_, e)| &**e) {
                Some(Expr::If(next)) => branch = next,
                Some(Expr::Block(b)) => {
                    bodies.push((b.block.stmts.clone(), Vec::new()));
                    break;
                }
                Some(other) => return Err(self.error(other, "this kind of `else`")),
                None => {
                    bodies.push((Vec::new(), Vec::new()));
                    break;
                }
            }
        }
        Ok(Arms {
            kind: BranchKind::If(conditions),
            bodies,
        })
    }

    fn match_arms(&self, m: &ExprMatch) -> syn::Result<Arms> {
        if self.depends(&m.expr) {
            return Err(self.error(&m.expr, "matching on the state (`match`)"));
        }
        let mut patterns = Vec::new();
        let mut bodies = Vec::new();
        for arm in &m.arms {
            let guard = arm.guard.as_ref().map(|(_, g)| (**g).clone());
            if let Some(g) = &guard
                && self.depends(g)
            {
                return Err(self.error(g, "a `match` guard that reads the state"));
            }
            let stmts = match &*arm.body {
                Expr::Block(b) if b.label.is_none() => b.block.stmts.clone(),
                body => vec![Stmt::Expr(body.clone(), None)],
            };
            bodies.push((stmts, pattern_names(&arm.pat)));
            patterns.push((arm.pat.clone(), guard));
        }
        Ok(Arms {
            kind: BranchKind::Match(m.expr.clone(), patterns),
            bodies,
        })
    }

    /// Lowers each arm with `each`, every arm from the same scopes, its prologue collected into
    /// one [`Branch`]; returns the selector and, per arm, `each`'s result and the scopes after it.
    fn lower_arms<T>(
        &mut self,
        arms: Arms,
        mut each: impl FnMut(&mut Self, &[Stmt]) -> syn::Result<T>,
    ) -> syn::Result<(u32, Vec<(T, Scopes)>)> {
        let selector = self.selectors;
        self.selectors += 1;
        let outer = std::mem::take(&mut self.prologue);
        let before = self.scopes.clone();
        let mut results = Vec::with_capacity(arms.bodies.len());
        let mut prologues = Vec::with_capacity(arms.bodies.len());
        for (stmts, names) in arms.bodies {
            self.scopes = before.clone();
            self.scopes.push(HashMap::new());
            for name in names {
                self.bind(name, None, false);
            }
            let result = each(self, &stmts);
            self.scopes.pop();
            let after = std::mem::replace(&mut self.scopes, before.clone());
            prologues.push(std::mem::take(&mut self.prologue));
            match result {
                Ok(value) => results.push((value, after)),
                Err(error) => {
                    self.prologue = outer;
                    return Err(error);
                }
            }
        }
        self.prologue = outer;
        self.prologue.push(Prologue::Branch(Box::new(Branch {
            selector,
            kind: arms.kind,
            arms: prologues,
        })));
        Ok((selector, results))
    }

    /// `if`/`match` as a statement: each arm's changes to locals are selected by the arm taken.
    fn branch_statement(&mut self, e: &Expr) -> syn::Result<()> {
        let arms = self.arms(e)?;
        let (selector, results) =
            self.lower_arms(arms, |l, stmts| match l.run(stmts, Context::Arm)? {
                Ending::Continue | Ending::Value(_) => Ok(()),
            })?;
        let scopes: Vec<Scopes> = results.into_iter().map(|(_, s)| s).collect();
        self.merge(selector, &scopes, e)
    }

    /// `if`/`match` as a value: the arms' values (and changes to locals) selected by the arm
    /// taken.
    pub(super) fn branch_value(&mut self, e: &Expr) -> syn::Result<Value> {
        let arms = self.arms(e)?;
        let (selector, results) =
            self.lower_arms(arms, |l, stmts| match l.run(stmts, Context::Block)? {
                Ending::Value(v) => Ok(v),
                Ending::Continue => Err(l.error(
                    e,
                    "a branch arm without a value (an `if` without `else` used as a value?)",
                )),
            })?;
        let (values, scopes): (Vec<Value>, Vec<Scopes>) = results.into_iter().unzip();
        self.merge(selector, &scopes, e)?;
        self.select(selector, values, e)
    }

    /// A branch with a `return` among the function's own statements: the rest of the function
    /// goes into every arm, and the function's value is selected by the arm taken.
    fn branch_returning(&mut self, e: &Expr, rest: &[Stmt]) -> syn::Result<Value> {
        let mut arms = self.arms(e)?;
        for (stmts, _) in &mut arms.bodies {
            // An arm's own final expression (`if c { m = 1.0 }`) is a statement once the rest
            // follows it.
            if !rest.is_empty()
                && let Some(Stmt::Expr(_, semi @ None)) = stmts.last_mut()
            {
                *semi = Some(Default::default());
            }
            stmts.extend_from_slice(rest);
        }
        let (selector, results) =
            self.lower_arms(arms, |l, stmts| match l.run(stmts, Context::Function)? {
                Ending::Value(v) => Ok(v),
                Ending::Continue => Err(l.error(
                    e,
                    "a branch after which the function has no value to return",
                )),
            })?;
        let values = results.into_iter().map(|(v, _)| v).collect();
        self.select(selector, values, e)
    }

    /// Brings the arms' scopes back together: every binding the arms left different is selected
    /// by the arm taken (a local the lowering does not follow is read back by name instead).
    fn merge(&mut self, selector: u32, arms: &[Scopes], at: &Expr) -> syn::Result<()> {
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
            let dependent = bindings.iter().any(|b| b.dependent);
            let values: Option<Vec<Value>> = bindings.iter().map(|b| b.value.clone()).collect();
            let value = match values {
                Some(values) => Some(self.select(selector, values, at)?),
                None if dependent => {
                    return Err(self.error(
                        at,
                        format_args!(
                            "a branch that gives `{name}` a state-dependent value in some arms \
                             and one odyn does not follow in others"
                        ),
                    ));
                }
                None => None,
            };
            self.scopes[level].insert(name, Binding { value, dependent });
        }
        Ok(())
    }

    /// `if selector == 0 { v₀ } else if selector == 1 { v₁ } … else { vₙ }`, part by part.
    fn select(&mut self, selector: u32, values: Vec<Value>, at: &Expr) -> syn::Result<Value> {
        let mut values = values;
        let mut merged = values.pop().expect("a branch has arms");
        while let Some(value) = values.pop() {
            let arm = u32::try_from(values.len()).expect("fewer than 2³² arms");
            merged = self.select_pair(selector, arm, value, merged, at)?;
        }
        Ok(merged)
    }

    fn select_pair(
        &mut self,
        selector: u32,
        arm: u32,
        then: Value,
        otherwise: Value,
        at: &Expr,
    ) -> syn::Result<Value> {
        match (then, otherwise) {
            (Value::Scalar(a), Value::Scalar(b)) => {
                Ok(Value::Scalar(self.graph.select(selector, arm, a, b)))
            }
            (Value::Vector(a), Value::Vector(b)) if a.len() == b.len() => Ok(Value::Vector(
                a.into_iter()
                    .zip(b)
                    .map(|(x, y)| self.graph.select(selector, arm, x, y))
                    .collect(),
            )),
            (Value::Tuple(a), Value::Tuple(b)) if a.len() == b.len() => Ok(Value::Tuple(
                a.into_iter()
                    .zip(b)
                    .map(|(x, y)| self.select_pair(selector, arm, x, y, at))
                    .collect::<syn::Result<_>>()?,
            )),
            _ => Err(self.error(at, "branch arms whose values have different shapes")),
        }
    }
}

/// The names `let` conditions in `cond` bind (`if let Some(x) = …`).
fn let_names(cond: &Expr) -> Vec<String> {
    struct Lets(Vec<String>);
    impl<'ast> syn::visit::Visit<'ast> for Lets {
        fn visit_expr_let(&mut self, l: &'ast syn::ExprLet) {
            self.0.extend(pattern_names(&l.pat));
        }
    }
    let mut lets = Lets(Vec::new());
    syn::visit::Visit::visit_expr(&mut lets, cond);
    lets.0
}
