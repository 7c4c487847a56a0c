//! The supported methods: one table of names, rules and the text error messages print.
//!
//! Every method is a rule from the receiver's (and arguments') values to the result's, built from
//! the graph's operations so [`crate::derivative`] differentiates it. Adding a method is adding a
//! row here (and, for a new function, its derivative in `derivative.rs`).

use syn::{Expr, Ident};

use super::{Lowering, Value};
use crate::ir::{Func, Func2};

/// Methods on a number with one number argument, built from graph operations.
const BINARY: [&str; 6] = ["atan2", "hypot", "min", "max", "powf", "powi"];
/// Methods on a number with two arguments.
const TERNARY: [&str; 2] = ["mul_add", "clamp"];
/// Methods on a vector.
const VECTOR: [&str; 7] = [
    "norm",
    "norm_squared",
    "normalize",
    "dot",
    "cross",
    "component_mul",
    "scale",
];

/// What the error messages list as supported.
pub(super) fn supported() -> String {
    let unary: Vec<&str> = Func::ALL.iter().map(|f| f.method()).collect();
    format!(
        "supported on the state: `+ - * /`, unary `-`, `let` (with tuple and slice patterns), \
         `if`/`match` on parameters (and `return` from them), `if` on the state on \
         comparisons joined by `&&`, `||`, `!`, `match`/`if let` on a number with ranges, \
         the methods {}, `recip`, \
         `sin_cos`, {}, {}, and on vectors `.x`/`[i]`, {}, `VectorN::new`",
        quoted(&unary),
        quoted(&BINARY),
        quoted(&TERNARY),
        quoted(&VECTOR),
    )
}

fn quoted(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

impl Lowering<'_> {
    /// `receiver.name(args)`, for a method call or its `f64::name(receiver, args)` form.
    pub(super) fn apply(
        &mut self,
        name: &str,
        receiver: Value,
        args: &[&Expr],
        at: &Ident,
    ) -> syn::Result<Value> {
        let unsupported = |l: &Self| l.error(at, format_args!("the method `{name}`"));
        match (receiver, args) {
            (value, []) if name == "clone" || name == "into_owned" || name == "to_owned" => {
                Ok(value)
            }
            (Value::Scalar(x), []) => {
                if name == "recip" {
                    let one = self.graph.num(1.0);
                    return Ok(Value::Scalar(self.graph.div(one, x)));
                }
                if name == "sin_cos" {
                    let (s, c) = (self.graph.call(Func::Sin, x), self.graph.call(Func::Cos, x));
                    return Ok(Value::Tuple(vec![Value::Scalar(s), Value::Scalar(c)]));
                }
                match Func::ALL.into_iter().find(|f| f.method() == name) {
                    Some(f) => Ok(Value::Scalar(self.graph.call(f, x))),
                    // State-free receivers stay the user's code (an opaque value), as before.
                    None if !self.graph.reads_variables(x) => Err(unsupported(self)),
                    None => Ok(Value::Scalar(self.extern_method(at, x, &[]))),
                }
            }
            (Value::Scalar(x), [n]) if name == "powi" => {
                let n = self.integer(n).ok_or_else(|| {
                    self.error(n, "a `powi` exponent that is not an integer constant")
                })?;
                Ok(Value::Scalar(self.graph.powi(x, n)))
            }
            (Value::Scalar(x), [y]) if name == "powf" => {
                if self.depends(y) {
                    return Err(self.error(
                        y,
                        "a state-dependent `powf` exponent (write `(y * x.ln()).exp()`)",
                    ));
                }
                let y = self.scalar(y)?;
                Ok(Value::Scalar(self.graph.powf(x, y)))
            }
            (Value::Scalar(a), [b]) if BINARY.contains(&name) => {
                let b = self.scalar(b)?;
                let g = &mut self.graph;
                Ok(Value::Scalar(match name {
                    "atan2" => g.call2(Func2::Atan2, a, b),
                    "hypot" => g.call2(Func2::Hypot, a, b),
                    // min: a where a ≤ b; max: a where a ≥ b (a at a tie, as Rust returns it).
                    "min" => g.pick(a, b, a, b),
                    _ => g.pick(b, a, a, b),
                }))
            }
            (Value::Scalar(a), [b, c]) if name == "mul_add" => {
                let (b, c) = (self.scalar(b)?, self.scalar(c)?);
                let product = self.graph.mul(a, b);
                Ok(Value::Scalar(self.graph.add(product, c)))
            }
            (Value::Scalar(x), [lo, hi]) if name == "clamp" => {
                // x.clamp(lo, hi) = min(max(x, lo), hi); at a bound, the bound's derivative.
                let (lo, hi) = (self.scalar(lo)?, self.scalar(hi)?);
                let g = &mut self.graph;
                let above = g.pick(lo, x, x, lo);
                Ok(Value::Scalar(g.pick(above, hi, above, hi)))
            }
            (Value::Vector(v), []) => {
                let squares = self.dot(&v, &v);
                match name {
                    "norm_squared" => Ok(Value::Scalar(squares)),
                    "norm" => Ok(Value::Scalar(self.graph.call(Func::Sqrt, squares))),
                    "normalize" => {
                        let norm = self.graph.call(Func::Sqrt, squares);
                        Ok(Value::Vector(
                            v.iter().map(|&x| self.graph.div(x, norm)).collect(),
                        ))
                    }
                    _ => Err(unsupported(self)),
                }
            }
            (Value::Vector(v), [other]) => {
                if name == "scale" {
                    let s = self.scalar(other)?;
                    return Ok(Value::Vector(
                        v.iter().map(|&x| self.graph.mul(x, s)).collect(),
                    ));
                }
                let Value::Vector(w) = self.expr(other)? else {
                    return Err(self.error(other, "a number where a vector is expected"));
                };
                if w.len() != v.len() {
                    return Err(self.error(other, "vectors of different lengths"));
                }
                match name {
                    "dot" => Ok(Value::Scalar(self.dot(&v, &w))),
                    "component_mul" => Ok(Value::Vector(
                        v.iter()
                            .zip(&w)
                            .map(|(&a, &b)| self.graph.mul(a, b))
                            .collect(),
                    )),
                    "cross" if v.len() == 3 => {
                        let mut c = Vec::with_capacity(3);
                        for (i, j) in [(1, 2), (2, 0), (0, 1)] {
                            let (p, q) = (self.graph.mul(v[i], w[j]), self.graph.mul(v[j], w[i]));
                            c.push(self.graph.sub(p, q));
                        }
                        Ok(Value::Vector(c))
                    }
                    _ => Err(unsupported(self)),
                }
            }
            (Value::Scalar(x), rest) if rest.len() <= 3 => {
                // Another method of a number, of numbers: evaluated as written, differentiated
                // by central differences of the call (`Jacobian::EXACT` false).
                let mut lowered = Vec::with_capacity(rest.len());
                for a in rest {
                    match self.expr(a)? {
                        Value::Scalar(id) => lowered.push(id),
                        _ => return Err(unsupported(self)),
                    }
                }
                if !std::iter::once(&x)
                    .chain(&lowered)
                    .any(|&id| self.graph.reads_variables(id))
                {
                    return Err(unsupported(self));
                }
                Ok(Value::Scalar(self.extern_method(at, x, &lowered)))
            }
            _ => Err(unsupported(self)),
        }
    }

    /// `receiver.method(args)` of a method the graph cannot see into, as an extern call of the
    /// closure `|r, a…| r.method(a…)`.
    fn extern_method(
        &mut self,
        method: &Ident,
        receiver: crate::ir::ExprId,
        args: &[crate::ir::ExprId],
    ) -> crate::ir::ExprId {
        let names: Vec<Ident> = (0..=args.len())
            .map(|i| quote::format_ident!("__odyn_a{}", i, span = proc_macro2::Span::mixed_site()))
            .collect();
        let (r, rest) = (&names[0], &names[1..]);
        let closure = quote::quote!((|#(#names: f64),*| -> f64 { #r.#method(#(#rest),*) }));
        let mut all = vec![receiver];
        all.extend_from_slice(args);
        self.graph.extern_call(closure, &all)
    }

    fn dot(&mut self, v: &[crate::ir::ExprId], w: &[crate::ir::ExprId]) -> crate::ir::ExprId {
        let mut sum = self.graph.num(0.0);
        for (&a, &b) in v.iter().zip(w) {
            let product = self.graph.mul(a, b);
            sum = self.graph.add(sum, product);
        }
        sum
    }
}
