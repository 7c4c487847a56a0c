//! Expressions: literals, paths, fields and indices, operators, branch values (calls are
//! [`super::calls`]), and the state literal `<Model>State { … }`; and the function's value as
//! f(t, y) in state layout.

use proc_macro2::TokenStream;
use quote::ToTokens;
use syn::{BinOp, Expr, ExprBinary, ExprField, Lit, Member, UnOp};

use super::names::path_name;
use super::{Lowering, MAX_DEPTH, Prologue, Value};
use crate::ir::{ExprId, Graph};
use crate::model::Shape;
use crate::syntax::int_literal;
use crate::syntax::is_self;

/// An arithmetic operator.
#[derive(Clone, Copy)]
pub(super) enum Arith {
    Add,
    Sub,
    Mul,
    Div,
}

/// The component a field access names: `.x` … `.w` of a vector, `.0` … of a tuple.
pub(super) fn component_index(f: &ExprField) -> Option<usize> {
    match &f.member {
        Member::Named(n) => ["x", "y", "z", "w"].iter().position(|c| n == c),
        Member::Unnamed(i) => Some(i.index as usize),
    }
}

impl Lowering<'_> {
    /// Lowers `e`; a state-independent expression the graph cannot express becomes opaque.
    pub(super) fn expr(&mut self, e: &Expr) -> syn::Result<Value> {
        if self.depth >= MAX_DEPTH {
            self.too_deep = true;
            return Err(self.refuse(
                e,
                format_args!(
                    "an expression nested more than {MAX_DEPTH} levels deep; split it with `let`s"
                ),
            ));
        }
        let prologue = self.prologue.len();
        let scopes =
            matches!(e, Expr::If(_) | Expr::Match(_) | Expr::Block(_)).then(|| self.scopes.clone());
        self.depth += 1;
        let lowered = self.structural(e);
        self.depth -= 1;
        match lowered {
            Ok(value) => Ok(value),
            // Too deep to follow is final: no opaque fallback (its tokens could be just as deep).
            Err(error) if self.too_deep => Err(error),
            Err(_) if !self.depends(e) => {
                // Whatever the failed attempt made opaque (`s` of `s.rest`) is part of `e` now.
                self.prologue.truncate(prologue);
                if let Some(scopes) = scopes {
                    self.scopes = scopes;
                }
                if self.reads_time(e) {
                    self.time_opaque = true;
                }
                Ok(Value::Scalar(self.opaque(e.to_token_stream())))
            }
            Err(error) => Err(error),
        }
    }

    pub(super) fn scalar(&mut self, e: &Expr) -> syn::Result<ExprId> {
        match self.expr(e)? {
            Value::Scalar(id) => Ok(id),
            _ => Err(self.error(e, "a vector where a number is expected")),
        }
    }

    /// An array literal's value: a vector of numbers, or rows of vectors of one length.
    fn array(&self, elements: Vec<Value>, at: impl ToTokens) -> syn::Result<Value> {
        if let Some(numbers) = elements
            .iter()
            .map(|e| match e {
                Value::Scalar(x) => Some(*x),
                _ => None,
            })
            .collect::<Option<Vec<_>>>()
        {
            return Ok(Value::Vector(numbers));
        }
        let rows: Option<Vec<Vec<ExprId>>> = elements
            .iter()
            .map(|e| match (e, &elements[0]) {
                (Value::Vector(a), Value::Vector(b)) if a.len() == b.len() => Some(a.clone()),
                _ => None,
            })
            .collect();
        if let Some(rows) = rows {
            Ok(Value::Rows(rows))
        } else {
            Err(self.error(
                at,
                "an array of other values than numbers or vectors of one length",
            ))
        }
    }

    pub(super) fn opaque(&mut self, tokens: TokenStream) -> ExprId {
        let index = self.opaques;
        self.opaques += 1;
        self.prologue.push(Prologue::Opaque(index, tokens));
        self.graph.opaque(index)
    }

    fn structural(&mut self, e: &Expr) -> syn::Result<Value> {
        match e {
            Expr::Lit(lit) => match &lit.lit {
                Lit::Float(f) => Ok(Value::Scalar(self.graph.num(f.base10_parse()?))),
                Lit::Int(i) => Ok(Value::Scalar(self.graph.num(i.base10_parse()?))),
                other => Err(self.error(other, "a literal that is not a number")),
            },
            Expr::Paren(p) => self.expr(&p.expr),
            Expr::Group(g) => self.expr(&g.expr),
            // nalgebra takes vector arguments by reference (`a.dot(&b)`): same value.
            Expr::Reference(r) if r.mutability.is_none() => self.expr(&r.expr),
            Expr::Path(p) => {
                let name = path_name(e).ok_or_else(|| self.error(p, "a path"))?;
                if let Some(binding) = self.lookup(&name) {
                    return match &binding.value {
                        Some(value) => Ok(value.clone()),
                        // Read by name in the prologue (`expr` makes it opaque).
                        None => Err(self.error(p, format_args!("`{name}`"))),
                    };
                }
                if self.is_time(&name)
                    && let Some((_, index)) = &self.time
                {
                    return Ok(Value::Scalar(self.graph.var(*index)));
                }
                Err(self.error(p, format_args!("`{name}`")))
            }
            Expr::Field(f) => self.field(f),
            Expr::Index(index) => {
                let base = self.expr(&index.expr)?;
                let i = self.known_index(&index.index).ok_or_else(|| {
                    self.error(
                        &index.index,
                        "an index that is not an integer literal (or a loop variable of an \
                         unrolled loop)",
                    )
                })?;
                self.component(&base, i, &index.index)
            }
            Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => {
                let value = self.expr(&u.expr)?;
                Ok(self.map(value, |g, x| g.neg(x)))
            }
            Expr::Binary(b) => self.binary(b),
            Expr::MethodCall(_) | Expr::Call(_) if self.helpers.called(e).is_some() => {
                self.inline_call(e)
            }
            Expr::MethodCall(m) => {
                let receiver = self.expr(&m.receiver)?;
                let args: Vec<&Expr> = m.args.iter().collect();
                self.apply(&m.method.to_string(), receiver, &args, &m.method)
            }
            Expr::Call(c) => self.call(c),
            Expr::Struct(s) => self.state_literal(s),
            Expr::Tuple(t) => Ok(Value::Tuple(
                t.elems
                    .iter()
                    .map(|e| self.expr(e))
                    .collect::<syn::Result<_>>()?,
            )),
            Expr::Array(a) => {
                let elements = a
                    .elems
                    .iter()
                    .map(|e| self.expr(e))
                    .collect::<syn::Result<Vec<_>>>()?;
                self.array(elements, a)
            }
            Expr::Repeat(r) => {
                let n = int_literal(&r.len).ok_or_else(|| {
                    self.error(&r.len, "an array length that is not an integer literal")
                })?;
                let element = self.expr(&r.expr)?;
                self.array(vec![element; n], r)
            }
            Expr::Block(b) if b.label.is_none() => self.block_value(&b.block),
            Expr::If(_) | Expr::Match(_) => self.branch_value(e),
            Expr::ForLoop(l) if self.depends(&l.expr) => {
                Err(self.error(&l.expr, "the state in a loop bound (`for`)"))
            }
            Expr::ForLoop(l) => {
                Err(self.error(l.for_token, "a loop whose body reads the state (`for`)"))
            }
            Expr::While(w) => Err(self.error(&w.cond, "a loop that reads the state (`while`)")),
            Expr::Loop(l) => Err(self.error(l.loop_token, "a loop that reads the state (`loop`)")),
            Expr::Cast(c) => Err(self.error(c, "a cast (`as`) of a state-dependent value")),
            Expr::Macro(m) => Err(self.error(m, "a macro call on the state")),
            Expr::Closure(c) => Err(self.error(c, "a closure over the state")),
            Expr::Return(r) => Err(self.refuse(
                r,
                "a `return` inside an expression; return from the function's own statements or \
                 from an `if`/`match` among them",
            )),
            other => Err(self.error(other, "this kind of expression")),
        }
    }

    fn field(&mut self, f: &ExprField) -> syn::Result<Value> {
        if is_self(&f.base) {
            let Member::Named(name) = &f.member else {
                return Err(self.error(f, "a tuple field of `self`"));
            };
            if let Some(offset) = self.offset(name) {
                let shape = self.model.field(name).expect("offset found it").shape;
                return Ok(self.state_value(offset, shape));
            }
            // A parameter: opaque, with its shape when it has one of the state shapes.
            return match self.parameter_shape(name) {
                Some(Shape::Scalar) | None => Ok(Value::Scalar(self.opaque(f.to_token_stream()))),
                Some(shape) => {
                    let reads = shape.component_reads(&f.to_token_stream());
                    Ok(self.shaped(shape, |l, i| l.opaque(reads[i].clone())))
                }
            };
        }
        let base = self.expr(&f.base)?;
        let index = component_index(f)
            .ok_or_else(|| self.error(&f.member, "a field other than `x`, `y`, `z`, `w`"))?;
        self.component(&base, index, &f.member)
    }

    pub(super) fn component(
        &mut self,
        base: &Value,
        i: usize,
        at: impl ToTokens,
    ) -> syn::Result<Value> {
        let past_end = matches!(base, Value::Vector(v) if i >= v.len())
            || matches!(base, Value::Tuple(t) if i >= t.len())
            || matches!(base, Value::Rows(r) if i >= r.len());
        if past_end && let Some(level) = self.guard {
            // In a loop bounded at run time: past the end at the iteration's own level, the
            // iteration cannot run (the code would panic), which caps the loop; inside an arm
            // of a branch, the arm cannot be taken (likewise), so its value is never used.
            if self.arms == level {
                self.past_end = true;
            } else {
                let zero = self.graph.num(0.0);
                return Ok(match base {
                    Value::Rows(r) => Value::Vector(vec![zero; r.first().map_or(0, Vec::len)]),
                    _ => Value::Scalar(zero),
                });
            }
        }
        match base {
            Value::Vector(v) if i < v.len() => Ok(Value::Scalar(v[i])),
            Value::Tuple(t) if i < t.len() => Ok(t[i].clone()),
            Value::Rows(r) if i < r.len() => Ok(Value::Vector(r[i].clone())),
            Value::Rows(r) => Err(self.refuse(
                at,
                format_args!("index {i} is past the end of an array of {} rows", r.len()),
            )),
            Value::Vector(v) => Err(self.refuse(
                at,
                format_args!(
                    "index {i} is past the end of a vector of {} components",
                    v.len()
                ),
            )),
            Value::Tuple(t) => Err(self.refuse(
                at,
                format_args!("`.{i}` is past the end of a tuple of {} values", t.len()),
            )),
            Value::Scalar(_) => Err(self.error(at, "a component of a number")),
        }
    }

    fn binary(&mut self, b: &ExprBinary) -> syn::Result<Value> {
        let op = match b.op {
            BinOp::Add(_) => Arith::Add,
            BinOp::Sub(_) => Arith::Sub,
            BinOp::Mul(_) => Arith::Mul,
            BinOp::Div(_) => Arith::Div,
            _ => {
                return Err(self.error(
                    b.op,
                    format_args!("the operator `{}`", b.op.to_token_stream()),
                ));
            }
        };
        let (left, right) = (self.expr(&b.left)?, self.expr(&b.right)?);
        self.arithmetic(&b.op.to_token_stream(), op, left, right)
    }

    pub(super) fn arithmetic(
        &mut self,
        at: &TokenStream,
        op: Arith,
        left: Value,
        right: Value,
    ) -> syn::Result<Value> {
        let g = &mut self.graph;
        let scalar = |g: &mut Graph, a, b| match op {
            Arith::Add => g.add(a, b),
            Arith::Sub => g.sub(a, b),
            Arith::Mul => g.mul(a, b),
            Arith::Div => g.div(a, b),
        };
        match (left, right) {
            (Value::Scalar(a), Value::Scalar(b)) => Ok(Value::Scalar(scalar(g, a, b))),
            (Value::Vector(a), Value::Vector(b))
                if a.len() == b.len() && matches!(op, Arith::Add | Arith::Sub) =>
            {
                Ok(Value::Vector(
                    a.into_iter().zip(b).map(|(x, y)| scalar(g, x, y)).collect(),
                ))
            }
            (Value::Scalar(s), Value::Vector(v)) if matches!(op, Arith::Mul) => {
                Ok(Value::Vector(v.into_iter().map(|x| g.mul(s, x)).collect()))
            }
            (Value::Vector(v), Value::Scalar(s)) if matches!(op, Arith::Mul | Arith::Div) => Ok(
                Value::Vector(v.into_iter().map(|x| scalar(g, x, s)).collect()),
            ),
            (Value::Vector(_), Value::Vector(_)) if matches!(op, Arith::Mul) => Err(self.error(
                at,
                "vector × vector (use `dot`, `cross` or `component_mul`)",
            )),
            _ => Err(self.error(at, "operands of mismatched shapes")),
        }
    }

    pub(super) fn map(
        &mut self,
        value: Value,
        f: impl Fn(&mut Graph, ExprId) -> ExprId + Copy,
    ) -> Value {
        match value {
            Value::Scalar(x) => Value::Scalar(f(&mut self.graph, x)),
            Value::Vector(v) => {
                Value::Vector(v.into_iter().map(|x| f(&mut self.graph, x)).collect())
            }
            Value::Tuple(t) => Value::Tuple(t.into_iter().map(|v| self.map(v, f)).collect()),
            Value::Rows(r) => Value::Rows(
                r.into_iter()
                    .map(|row| row.into_iter().map(|x| f(&mut self.graph, x)).collect())
                    .collect(),
            ),
        }
    }

    pub(super) fn integer(&self, e: &Expr) -> Option<i32> {
        match e {
            Expr::Lit(_) | Expr::Group(_) | Expr::Paren(_) => {
                int_literal(e).and_then(|n| i32::try_from(n).ok())
            }
            Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => self.integer(&u.expr).map(|n| -n),
            _ => None,
        }
    }
}
