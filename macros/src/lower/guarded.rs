//! Loops on the state bounded at run time (see `loops` for those unrolled at compile time).
//!
//! A bound or condition that reads only parameters (`0..self.n`, `while i < self.n`) is known
//! only at run time. Such a loop is unrolled as far as it can run without indexing past the end
//! of a vector or array (the original code panics beyond that, so no run goes further), each
//! iteration guarded by the loop's own test, a branch on parameters: `for k in a..end` becomes
//! `let end' = end; if a < end' { let k = a; body; if a + 1 < end' { … } }`, and
//! `while c { body }` becomes `if c { body; if c { body; … } }`: nested, since each test runs
//! only after the iterations before it, so locals the body changes (a counter) stay known from
//! one iteration to the next. Up to 64 iterations nest; a longer `for` gets one flat test per
//! iteration (a counter changed by its body is then refused), a longer `while` is refused. The
//! most iterations are found by lowering the body, unguarded, until an index goes past the end
//! at the iteration's own level, or in the first iteration of an inner `for` to the same end
//! (which runs whenever the outer iteration does); a loop whose body indexes nothing of a known
//! length is refused. Past an end inside a branch of such a loop's body (`if i + 1 <
//! self.n { self.x[i + 1] } else { 0.0 }` at the last i), the arm cannot be taken — the code
//! would panic if it were — so it reads zero there and the iteration still counts.

use proc_macro2::TokenStream;
use quote::ToTokens;
use syn::{Expr, ExprForLoop, ExprWhile, RangeLimits, Stmt};

use super::loops::MAX_ITERATIONS;
use super::statements::Context;
use super::{Lowering, Value};

/// A `for` loop bounded at run time whose iterations are being tried (see
/// [`Lowering::implied`]).
pub(super) struct Trial {
    /// The end's tokens, as a string.
    end: String,
    /// Whether the range is `a..end` (else `a..=end`).
    half_open: bool,
    /// The loop variable's value in the iteration being tried.
    value: i64,
}

/// Most iterations of a loop bounded at run time whose tests nest (see [`nested`]): the
/// generated code nests as deep. A longer `while` is refused, a longer `for` gets flat tests.
const MAX_NESTED: usize = 64;

/// `if test₀ { if true { body₀ } if test₁ { if true { body₁ } … } }`: each iteration's test runs
/// only after the iterations before it ran, so the locals they change (a counter) stay known in
/// the next; `if true` gives each body a scope of its own.
fn nested(iterations: impl DoubleEndedIterator<Item = (TokenStream, Vec<Stmt>)>) -> Vec<Stmt> {
    let mut nest: Vec<Stmt> = Vec::new();
    for (test, body) in iterations.rev() {
        nest = vec![syn::parse_quote!(if #test { if true { #(#body)* } #(#nest)* })];
    }
    nest
}

impl Lowering<'_> {
    /// `for k in a..end` whose end reads parameters: guarded iterations, as many as the body can
    /// run without indexing past an end.
    pub(super) fn guarded_for(
        &mut self,
        l: &ExprForLoop,
        name: Option<&syn::Ident>,
    ) -> syn::Result<()> {
        let Expr::Range(r) = &*l.expr else {
            return Err(self.unknown_bound(&l.expr));
        };
        let (Some(start), Some(end)) = (&r.start, &r.end) else {
            return Err(self.unknown_bound(&l.expr));
        };
        let Some(first) = self.known_integer(start) else {
            return Err(self.unknown_bound(&l.expr));
        };
        let end_name = quote::format_ident!("__odyn_end{}", self.selectors);
        // The loop variable has the end's type in the prologue, as in the user's loop (a bare
        // literal would be `{integer}`, and `i.pow(2)` would not compile).
        let bind = |k: i64| {
            let literal = proc_macro2::Literal::i64_unsuffixed(k);
            name.map(|n| -> syn::Stmt {
                syn::parse_quote!(let #n = ::odyn::__private::same_type(#literal, &#end_name);)
            })
        };
        let trial = Trial {
            end: end.to_token_stream().to_string(),
            half_open: matches!(r.limits, RangeLimits::HalfOpen(_)),
            value: first,
        };
        let implied = self.implied(end, &trial);
        // Tried with its own entry last in `trials` (loops inside push and pop their own).
        self.trials.push(trial);
        let count = self.most_iterations(&l.expr, |this, j| {
            let k = first + j as i64;
            if let Some(trial) = this.trials.last_mut() {
                trial.value = k;
            }
            let variable = bind(k).map(|stmt| {
                let name = name.expect("a binding has a name").to_string();
                (name, Value::Scalar(this.graph.num(k as f64)), stmt)
            });
            this.iteration(&l.body, variable).map(|()| true)
        });
        self.trials.pop();
        let count = count?;
        // No iteration can run, and the first would run whenever the iteration of an enclosing
        // loop being tried does: that iteration cannot run either (`for j in 0..self.n` inside
        // `for i in 0..self.n`, at i = 0 ⇒ n ≥ 1 ⇒ j = 0 runs). The enclosing loop's cap.
        if count == 0 && implied && self.guard == Some(self.arms) {
            self.past_end = true;
        }
        let mut stmts: Vec<syn::Stmt> = vec![syn::parse_quote!(let #end_name = #end;)];
        let test = match r.limits {
            RangeLimits::HalfOpen(_) => quote::quote!(<),
            RangeLimits::Closed(_) => quote::quote!(<=),
        };
        let iterations = (0..count).map(|j| {
            let k = first + j as i64;
            let literal = proc_macro2::Literal::i64_unsuffixed(k);
            let mut body: Vec<syn::Stmt> = bind(k).into_iter().collect();
            body.extend(l.body.stmts.iter().cloned());
            (quote::quote!(#literal #test #end_name), body)
        });
        if count <= MAX_NESTED {
            stmts.extend(nested(iterations));
        } else {
            // One flat test per iteration (a counter the body changes is then not followed).
            stmts
                .extend(iterations.map(|(test, body)| -> syn::Stmt {
                    syn::parse_quote!(if #test { #(#body)* })
                }));
        }
        self.count_iterations(count, &l.expr)?;
        self.guarded(&stmts)
    }

    /// Whether the first iteration of loop `inner` (ending at `end`) runs whenever the
    /// iteration of an enclosing loop being tried runs: the same end, reading no local, and
    /// `inner` starting no later than that loop's variable (`first < end` follows from
    /// `k < end`).
    fn implied(&self, end: &Expr, inner: &Trial) -> bool {
        // An end that reads a local may have changed since the enclosing loop read it; one
        // of `self`'s fields and constants has not.
        if self.reads_locals(&end.to_token_stream()) {
            return false;
        }
        let first = inner.value;
        self.trials.iter().any(|outer| {
            outer.end == inner.end
                && first <= outer.value
                && (outer.half_open || !inner.half_open || first < outer.value)
        })
    }

    /// `while c` whose condition reads parameters: guarded iterations, nested, as many as the
    /// body can run without indexing past an end (or until `c` is known to be false).
    pub(super) fn guarded_while(&mut self, w: &ExprWhile) -> syn::Result<()> {
        let count = self.most_iterations(&w.cond, |this, _| {
            if this.known_condition(&w.cond) == Some(false) {
                return Ok(false);
            }
            this.iteration(&w.body, None).map(|()| true)
        })?;
        if count > MAX_NESTED {
            return Err(self.refuse(
                &w.cond,
                format_args!(
                    "a `while` loop on the state whose condition is known only at run time and \
                     that may run more than {MAX_NESTED} times (odyn nests one test per \
                     iteration); write it as `for k in 0..n`"
                ),
            ));
        }
        let (cond, body) = (&w.cond, &w.body.stmts);
        let nest = nested((0..count).map(|_| (cond.to_token_stream(), body.clone())));
        self.count_iterations(count, &w.cond)?;
        self.guarded(&nest)
    }

    /// Lowers a guarded loop's statements: every iteration inside its guard's arm, so an index
    /// past an end there is in an arm that cannot be taken (see [`Lowering::component`]).
    fn guarded(&mut self, stmts: &[syn::Stmt]) -> syn::Result<()> {
        let outer = self.guard.replace(self.arms);
        let result = self.run(stmts, Context::Arm).map(|_| ());
        self.guard = outer;
        result
    }

    /// How many iterations a loop bounded at run time can run: `iteration(self, j)` lowers
    /// iteration j unguarded (or returns `false` when the loop is known to end there) until an
    /// index goes past an end. Everything the trial lowered is undone.
    fn most_iterations(
        &mut self,
        at: &Expr,
        mut iteration: impl FnMut(&mut Self, usize) -> syn::Result<bool>,
    ) -> syn::Result<usize> {
        let (scopes, prologue, opaques, selectors) = (
            self.scopes.clone(),
            self.prologue.len(),
            self.opaques,
            self.selectors,
        );
        let (iterations, time_opaque, past_end, guard) =
            (self.iterations, self.time_opaque, self.past_end, self.guard);
        self.guard = Some(self.arms);
        let mut count = 0;
        let outcome = loop {
            if self.iterations + count >= MAX_ITERATIONS {
                break Err(self.refuse(
                    at,
                    "a loop on the state whose bound is known only at run time and whose body \
                     indexes no array or vector of a known length with its variable, outside \
                     branches and inner loops (but an inner `for` from 0 to the same bound of \
                     `self`'s fields) (odyn unrolls loops on the state: a run-time \
                     bound needs an index, such as `self.x[k]` of `for k in 0..self.n`, that \
                     stops it; or write the bound as an integer literal, or take the Jacobian \
                     by `jacobian = dual` or `jacobian = finite_differences`)",
                ));
            }
            self.past_end = false;
            match iteration(self, count) {
                Ok(true) if !self.past_end => count += 1,
                Ok(_) => break Ok(count),
                Err(_) if self.past_end => break Ok(count),
                Err(error) => break Err(error),
            }
        };
        self.scopes = scopes;
        self.prologue.truncate(prologue);
        (self.opaques, self.selectors) = (opaques, selectors);
        (self.iterations, self.time_opaque, self.past_end) = (iterations, time_opaque, past_end);
        self.guard = guard;
        outcome
    }
}
