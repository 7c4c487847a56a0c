//! Branches on parameters — `if`/`match` whose conditions do not read the state — as statements
//! and as values, with early `return`s from them: each arm is lowered in its own scope, and the
//! locals the arms change, and the branch's value, are selected by the arm the prologue's copy of
//! the branch took.

use std::collections::HashMap;

use syn::{Expr, ExprIf, ExprMatch, Stmt};

use super::scope::{Binding, pattern_names};
use super::statements::{Context, Ending};
use super::{Branch, BranchKind, Lowering, Prologue, Value};

/// The arms of a branch as statement lists, with the names each arm's pattern binds.
struct Arms {
    kind: BranchKind,
    bodies: Vec<(Vec<Stmt>, Vec<String>)>,
}

type Scopes = Vec<HashMap<String, Binding>>;

impl Lowering<'_> {
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
    pub(super) fn branch_statement(&mut self, e: &Expr) -> syn::Result<()> {
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
    pub(super) fn branch_returning(&mut self, e: &Expr, rest: &[Stmt]) -> syn::Result<Value> {
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
