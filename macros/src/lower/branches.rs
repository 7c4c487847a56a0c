//! Branches — `if`/`match` — as statements and as values, with early `return`s from them: each
//! arm is lowered in its own scope, and the locals the arms change, and the branch's value, are
//! chosen by the arm taken ([`super::merge`]).
//!
//! - A branch on parameters (its conditions do not read the state) is chosen by the prologue's
//!   copy of the branch, which records the arm it took in a selector ([`crate::ir::Node::Select`]).
//! - An `if` on the state, each condition comparisons (`<`, `<=`, `>`, `>=`) of two numbers
//!   and parameter-only conditions joined by `&&`, `||` and `!`, is chosen in the graph by those comparisons
//!   ([`crate::ir::Node::Pick`], as `min` and `max` are). Each arm is differentiated on its own: the Jacobian is the taken arm's, and at the
//!   switching surface it is the one-sided derivative of the arm the comparison chose there.
//! - A `match` or `if let` on the state is the `if` chain it means ([`super::matches`]).

use std::collections::HashMap;

use syn::{Expr, ExprIf, ExprMatch, Stmt};

use super::conditions::Condition;
use super::names::{let_names, pattern_names};
use super::scope::{Scopes, changes_outer};
use super::statements::{Context, Ending};
use super::{Branch, BranchKind, Lowering, Prologue, Value};

/// The arms of a branch as statement lists, with the names each arm's pattern binds.
struct Arms {
    kind: BranchKind,
    bodies: Vec<(Vec<Stmt>, Vec<String>)>,
    /// The conditions read the state: the arms are chosen in the graph.
    on_state: bool,
}

/// How the arm taken is chosen.
pub(super) enum Chooser {
    /// By the selector the prologue's copy of a branch on parameters sets.
    Selector(u32),
    /// By conditions on graph values, one per arm but the last (the `else`).
    Conditions(Vec<Condition>),
}

impl Lowering<'_> {
    /// The arms of `if`/`match` `e` (a `match` on the state is an `if` chain by then).
    fn arms(&self, e: &Expr) -> syn::Result<Arms> {
        match e {
            Expr::If(i) => self.if_arms(i),
            Expr::Match(m) => self.match_arms(m),
            other => Err(self.error(other, "this kind of branch")),
        }
    }

    fn if_arms(&self, mut branch: &ExprIf) -> syn::Result<Arms> {
        let (mut conditions, mut bodies) = (Vec::new(), Vec::new());
        let on_state = self.depends_any(branch);
        loop {
            if on_state && let Err(at) = self.check_condition(&branch.cond) {
                return Err(self.error(
                    at,
                    "this condition on the state (`if` on the state takes comparisons, `a < b`, \
                     `a <= b`, `a > b`, `a >= b`, `a == b` or `a != b`, and parameter-only conditions, joined by \
                     `&&`, `||` and `!`; `min`, `max` and `clamp` are exact too)",
                ));
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
            on_state,
        })
    }

    /// Whether any condition of the `if`/`else if` chain from `branch` reads the state.
    fn depends_any(&self, mut branch: &ExprIf) -> bool {
        loop {
            if self.depends(&branch.cond) {
                return true;
            }
            match branch.else_branch.as_ref().map(|(_, e)| &**e) {
                Some(Expr::If(next)) => branch = next,
                _ => return false,
            }
        }
    }

    /// A `match` on parameters: a `match` whose scrutinee or guards read the state is an `if`
    /// chain by then ([`Lowering::state_match`]).
    fn match_arms(&self, m: &ExprMatch) -> syn::Result<Arms> {
        let mut patterns = Vec::new();
        let mut bodies = Vec::new();
        for arm in &m.arms {
            let guard = arm.guard.as_ref().map(|(_, g)| (**g).clone());
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
            on_state: false,
        })
    }

    /// Lowers each arm with `each`, every arm from the same scopes; returns how the arm taken
    /// is chosen and, per arm, `each`'s result and the scopes after it. The arms' prologues go
    /// into one [`Branch`]: for a branch on parameters, the prologue's copy of the branch runs
    /// the taken arm's; for one on the state, every arm's runs (they compute parameter-only
    /// values), each in its own block.
    fn lower_arms<T>(
        &mut self,
        arms: Arms,
        mut each: impl FnMut(&mut Self, &[Stmt]) -> syn::Result<T>,
    ) -> syn::Result<(Chooser, Vec<(T, Scopes)>)> {
        let Arms {
            kind,
            bodies,
            on_state,
        } = arms;
        let chooser = match &kind {
            // The conditions on the state, lowered in the scope before the arms.
            BranchKind::If(conditions) if on_state => {
                Chooser::Conditions(self.conditions(conditions)?)
            }
            _ => {
                self.selectors += 1;
                Chooser::Selector(self.selectors - 1)
            }
        };
        let outer = std::mem::take(&mut self.prologue);
        let before = self.scopes.clone();
        let mut results = Vec::with_capacity(bodies.len());
        let mut prologues = Vec::with_capacity(bodies.len());
        for (stmts, names) in bodies {
            self.scopes = before.clone();
            self.scopes.push(HashMap::new());
            for name in names {
                self.bind(name, None, false);
            }
            self.arms += 1;
            let result = each(self, &stmts);
            self.arms -= 1;
            self.scopes.pop();
            let after = std::mem::replace(&mut self.scopes, before.clone());
            let prologue = std::mem::take(&mut self.prologue);
            let result = result.and_then(|value| match on_state {
                true => self.runs_in_every_arm(&prologue, &before).map(|()| value),
                false => Ok(value),
            });
            match result {
                Ok(value) => results.push((value, after)),
                Err(error) => {
                    self.prologue = outer;
                    return Err(error);
                }
            }
            prologues.push(prologue);
        }
        self.prologue = outer;
        let (selector, kind) = match chooser {
            Chooser::Selector(selector) => (selector, kind),
            // No selector: every arm's prologue runs.
            Chooser::Conditions(_) => (u32::MAX, BranchKind::Every),
        };
        if !matches!(kind, BranchKind::Every) || prologues.iter().any(|p| !p.is_empty()) {
            self.prologue.push(Prologue::Branch(Box::new(Branch {
                selector,
                kind,
                arms: prologues,
            })));
        }
        Ok((chooser, results))
    }

    /// Refuses an arm of an `if` on the state whose prologue changes a local from `before` the
    /// branch: every arm's prologue runs, so the change would reach the arms after it and the
    /// code after the branch.
    fn runs_in_every_arm(&self, prologue: &[Prologue], before: &Scopes) -> syn::Result<()> {
        match changes_outer(prologue, before) {
            None => Ok(()),
            Some((stmt, name)) => Err(self.refuse(
                stmt,
                format_args!(
                    "parameter-only code inside an `if` on the state (or after a `return` from \
                     one) changes `{name}`, a local from before the `if`: odyn runs such code \
                     whichever arm the state takes; give `{name}` its value as the `if`'s value \
                     instead (`let {name} = if … {{ a }} else {{ b }};`)"
                ),
            )),
        }
    }

    /// `if`/`match` as a statement: each arm's changes to locals are selected by the arm taken.
    pub(super) fn branch_statement(&mut self, e: &Expr) -> syn::Result<()> {
        if let Some(chain) = self.state_match(e, &[]) {
            let chain = chain?;
            self.scopes.push(HashMap::new());
            let ran = self.run(&chain.block().stmts, Context::Arm);
            self.scopes.pop();
            return ran.map(|_| ());
        }
        if let Some(stmts) = self.known_arm(e) {
            return self.known_arm_lowered(&stmts, Context::Arm).map(|_| ());
        }
        let arms = self.arms(e)?;
        let (chooser, results) =
            self.lower_arms(arms, |l, stmts| match l.run(stmts, Context::Arm)? {
                Ending::Continue | Ending::Value(_) => Ok(()),
            })?;
        let scopes: Vec<Scopes> = results.into_iter().map(|(_, s)| s).collect();
        self.merge(&chooser, &scopes, e)
    }

    /// `if`/`match` as a value: the arms' values (and changes to locals) selected by the arm
    /// taken.
    pub(super) fn branch_value(&mut self, e: &Expr) -> syn::Result<Value> {
        if let Some(chain) = self.state_match(e, &[]) {
            return self.block_value(&chain?.block());
        }
        if let Some(stmts) = self.known_arm(e) {
            return match self.known_arm_lowered(&stmts, Context::Block)? {
                Ending::Value(v) => Ok(v),
                Ending::Continue => Err(self.error(
                    e,
                    "a branch arm without a value (an `if` without `else` used as a value?)",
                )),
            };
        }
        let arms = self.arms(e)?;
        let (chooser, results) =
            self.lower_arms(arms, |l, stmts| match l.run(stmts, Context::Block)? {
                Ending::Value(v) => Ok(v),
                Ending::Continue => Err(l.error(
                    e,
                    "a branch arm without a value (an `if` without `else` used as a value?)",
                )),
            })?;
        let (values, scopes): (Vec<Value>, Vec<Scopes>) = results.into_iter().unzip();
        self.merge(&chooser, &scopes, e)?;
        self.select(&chooser, values, e)
    }

    /// The statements of the arm an `if` takes when its conditions are known at compile time
    /// (`if k > 0` on the variable of an unrolled loop): only that arm is lowered, so the others
    /// may do what the iteration could not (`self.x[k - 1]` at k = 0).
    fn known_arm(&mut self, e: &Expr) -> Option<Vec<Stmt>> {
        let Expr::If(first) = e else { return None };
        let mut branch = first;
        loop {
            if !self.known_condition(&branch.cond)? {
                match branch.else_branch.as_ref().map(|(_, e)| &**e) {
                    Some(Expr::If(next)) => branch = next,
                    Some(Expr::Block(b)) => return Some(b.block.stmts.clone()),
                    Some(_) => return None,
                    None => return Some(Vec::new()),
                }
            } else {
                return Some(branch.then_branch.stmts.clone());
            }
        }
    }

    /// The arm [`Self::known_arm`] chose, in a scope of its own, its prologue in a block.
    fn known_arm_lowered(&mut self, stmts: &[Stmt], context: Context) -> syn::Result<Ending> {
        let outer = std::mem::take(&mut self.prologue);
        self.scopes.push(HashMap::new());
        let ending = self.run(stmts, context);
        self.scopes.pop();
        let own = std::mem::replace(&mut self.prologue, outer);
        let ending = ending?;
        if !own.is_empty() {
            self.prologue.push(Prologue::Branch(Box::new(Branch {
                selector: u32::MAX,
                kind: BranchKind::Every,
                arms: vec![own],
            })));
        }
        Ok(ending)
    }

    /// A branch with a `return` among the function's own statements: the rest of the function
    /// goes into every arm, and the function's value is selected by the arm taken.
    pub(super) fn branch_returning(&mut self, e: &Expr, rest: &[Stmt]) -> syn::Result<Value> {
        if let Some(chain) = self.state_match(e, rest) {
            // The names go into the function's scope; `state_match` checked that `rest` does
            // not read them.
            let super::matches::Chain { lets, chain } = chain?;
            self.run(&lets, Context::Arm)?;
            return self.branch_returning(&chain, rest);
        }
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
        let (chooser, results) =
            self.lower_arms(arms, |l, stmts| match l.run(stmts, Context::Function)? {
                Ending::Value(v) => Ok(v),
                Ending::Continue => Err(l.error(
                    e,
                    "a branch after which the function has no value to return",
                )),
            })?;
        let values = results.into_iter().map(|(v, _)| v).collect();
        self.select(&chooser, values, e)
    }
}
