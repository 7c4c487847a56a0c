//! Stage 4: lowering a force function's body from syn into the expression graph.
//!
//! Only what depends on the state must be understood: any sub-expression that does not (a
//! parameter, the time, a call on parameters, a constant) becomes an opaque leaf, evaluated by the
//! user's own code before the Jacobian. What does depend on the state must be built from the
//! supported operations; anything else is an error at that sub-expression, naming what is
//! supported.

use std::collections::HashMap;

use proc_macro2::TokenStream;
use quote::{ToTokens, quote};
use syn::visit::{self, Visit};
use syn::{
    BinOp, Block, Expr, ExprBinary, ExprField, ExprMethodCall, Ident, Lit, Member, Pat, Stmt, UnOp,
};

use crate::ir::{ExprId, Func, Graph};
use crate::model::{Model, Order, Role, Shape, int_literal, shape_of};

/// What the supported operations are, for error messages.
const SUPPORTED: &str = "supported on the state: `+ - * /`, unary `-`, `let`, `powi`, `powf`, \
    `sqrt`, `exp`, `ln`, `sin`, `cos`, `tan`, `tanh`, `abs`, `recip`, `mul_add`, and on vectors \
    `.x`/`[i]`, `dot`, `cross`, `norm`, `norm_squared`, `normalize`, `component_mul`, `scale`, \
    `VectorN::new`";

/// A lowered force function.
pub(crate) struct Lowered {
    pub(crate) graph: Graph,
    /// f(t, y) component by component, in state layout order.
    pub(crate) outputs: Vec<ExprId>,
    /// What runs before the Jacobian: the body's state-independent statements and the opaque
    /// values, in source order.
    pub(crate) prologue: Vec<Prologue>,
}

/// One statement of the prologue.
pub(crate) enum Prologue {
    /// A state-independent statement of the user's, kept so opaque values can name its locals.
    Stmt(Box<Stmt>),
    /// Opaque value `index`, computed by the user's expression.
    Opaque(usize, TokenStream),
}

/// The value of a sub-expression.
#[derive(Clone, Debug)]
enum Value {
    Scalar(ExprId),
    Vector(Vec<ExprId>),
    Tuple(Vec<Value>),
}

struct Binding {
    value: Value,
    dependent: bool,
}

struct Lowering<'m> {
    model: &'m Model<'m>,
    function: String,
    time: Option<Ident>,
    graph: Graph,
    prologue: Vec<Prologue>,
    opaques: usize,
    scopes: Vec<HashMap<String, Binding>>,
}

/// Lowers the body of `f`, the model's `acceleration` or `derivative`.
pub(crate) fn lower(model: &Model<'_>, f: &syn::ImplItemFn) -> syn::Result<Lowered> {
    let time = f.sig.inputs.iter().nth(1).and_then(|arg| match arg {
        syn::FnArg::Typed(t) => match &*t.pat {
            Pat::Ident(p) => Some(p.ident.clone()),
            _ => None,
        },
        syn::FnArg::Receiver(_) => None,
    });
    let mut l = Lowering {
        model,
        function: f.sig.ident.to_string(),
        time,
        graph: Graph::default(),
        prologue: Vec::new(),
        opaques: 0,
        scopes: vec![HashMap::new()],
    };
    let value = l.block(&f.block)?;
    let outputs = l.outputs(value, f)?;
    Ok(Lowered {
        graph: l.graph,
        outputs,
        prologue: l.prologue,
    })
}

/// Lowers a particle kernel. `vectors` are its D-vector arguments, bound in order to the graph
/// variables D·k … D·k + D − 1; `model` supplies only parameter shapes (its `states` are empty).
/// The body's value, a D-vector, is the output.
pub(crate) fn lower_kernel(
    model: &Model<'_>,
    f: &syn::ImplItemFn,
    vectors: &[Ident],
    dim: usize,
) -> syn::Result<Lowered> {
    let mut l = Lowering {
        model,
        function: f.sig.ident.to_string(),
        time: None,
        graph: Graph::default(),
        prologue: Vec::new(),
        opaques: 0,
        scopes: vec![HashMap::new()],
    };
    for (k, name) in vectors.iter().enumerate() {
        let parts = (0..dim).map(|i| l.graph.var(dim * k + i)).collect();
        l.bind(name.to_string(), Value::Vector(parts), true);
    }
    let outputs = match l.block(&f.block)? {
        Value::Vector(v) if v.len() == dim => v,
        _ => {
            return Err(l.error(
                &f.sig.output,
                format_args!("a kernel value that is not a {dim}-vector force"),
            ));
        }
    };
    Ok(Lowered {
        graph: l.graph,
        outputs,
        prologue: l.prologue,
    })
}

impl Lowering<'_> {
    fn error(&self, tokens: impl ToTokens, what: impl std::fmt::Display) -> syn::Error {
        syn::Error::new_spanned(
            tokens,
            format!(
                "{what} in `{}`, so odyn cannot derive its Jacobian; {SUPPORTED} \
                 (or add `jacobian = false` to `#[system]` to use explicit methods only)",
                self.function
            ),
        )
    }

    // ----- statements -------------------------------------------------------------------------

    fn block(&mut self, block: &Block) -> syn::Result<Value> {
        self.scopes.push(HashMap::new());
        let result = self.statements(block);
        self.scopes.pop();
        result
    }

    fn statements(&mut self, block: &Block) -> syn::Result<Value> {
        let Some((last, init)) = block.stmts.split_last() else {
            return Err(self.error(block, "an empty body"));
        };
        for stmt in init {
            self.statement(stmt)?;
        }
        match last {
            Stmt::Expr(e, None) => self.expr(e),
            other => Err(self.error(other, "a body that does not end in an expression")),
        }
    }

    fn statement(&mut self, stmt: &Stmt) -> syn::Result<()> {
        match stmt {
            Stmt::Local(local) => {
                let name = pattern_name(&local.pat).ok_or_else(|| {
                    self.error(&local.pat, "a `let` pattern other than a plain name")
                })?;
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
                self.bind(name, value, dependent);
                Ok(())
            }
            Stmt::Expr(Expr::Assign(assign), Some(_)) => {
                let value = self.expr(&assign.right)?;
                self.reassign(
                    stmt,
                    &assign.left,
                    |_, _| Ok(value),
                    self.depends(&assign.right),
                )
            }
            Stmt::Expr(Expr::Binary(b), Some(_)) if compound(&b.op).is_some() => {
                let op = compound(&b.op).expect("checked by the guard");
                let rhs = self.expr(&b.right)?;
                let dependent = self.depends(&b.right);
                let span = b.op.to_token_stream();
                self.reassign(
                    stmt,
                    &b.left,
                    |l, old| l.arithmetic(&span, op, old, rhs),
                    dependent,
                )
            }
            Stmt::Item(_) => {
                self.prologue.push(Prologue::Stmt(Box::new(stmt.clone())));
                Ok(())
            }
            Stmt::Expr(e, _) if !self.depends(e) => Ok(()),
            Stmt::Macro(m) if !self.depends_tokens(&m.mac.tokens) => Ok(()),
            // A loop or branch statement: its own error says which part reads the state.
            Stmt::Expr(
                e @ (Expr::ForLoop(_)
                | Expr::While(_)
                | Expr::Loop(_)
                | Expr::If(_)
                | Expr::Match(_)),
                _,
            ) => self.structural(e).map(|_| ()),
            other => Err(self.error(
                other,
                "a statement other than `let` or an assignment to a local",
            )),
        }
    }

    /// `name = …` or `name op= …` on a local.
    fn reassign(
        &mut self,
        stmt: &Stmt,
        target: &Expr,
        update: impl FnOnce(&mut Self, Value) -> syn::Result<Value>,
        rhs_dependent: bool,
    ) -> syn::Result<()> {
        let Some(name) = path_name(target) else {
            return Err(self.error(target, "assigning to something other than a local"));
        };
        let Some(old) = self.lookup(&name).map(|b| (b.value.clone(), b.dependent)) else {
            return Err(self.error(
                target,
                format_args!("assigning to `{name}`, which is not a local"),
            ));
        };
        let value = update(self, old.0)?;
        let dependent = old.1 || rhs_dependent;
        if !dependent {
            self.prologue.push(Prologue::Stmt(Box::new(stmt.clone())));
        }
        for scope in self.scopes.iter_mut().rev() {
            if let Some(binding) = scope.get_mut(&name) {
                *binding = Binding { value, dependent };
                break;
            }
        }
        Ok(())
    }

    fn bind(&mut self, name: String, value: Value, dependent: bool) {
        let scope = self.scopes.last_mut().expect("there is always a scope");
        scope.insert(name, Binding { value, dependent });
    }

    fn lookup(&self, name: &str) -> Option<&Binding> {
        self.scopes.iter().rev().find_map(|scope| scope.get(name))
    }

    // ----- dependence -------------------------------------------------------------------------

    fn depends(&self, e: &Expr) -> bool {
        let mut finder = Depends {
            lowering: self,
            found: false,
        };
        finder.visit_expr(e);
        finder.found
    }

    fn depends_tokens(&self, tokens: &TokenStream) -> bool {
        tokens.clone().into_iter().any(|tree| match tree {
            proc_macro2::TokenTree::Ident(i) => {
                self.lookup(&i.to_string()).is_some_and(|b| b.dependent)
            }
            proc_macro2::TokenTree::Group(g) => self.depends_tokens(&g.stream()),
            _ => false,
        })
    }

    // ----- expressions ------------------------------------------------------------------------

    /// Lowers `e`; a state-independent expression the graph cannot express becomes opaque.
    fn expr(&mut self, e: &Expr) -> syn::Result<Value> {
        let prologue = self.prologue.len();
        match self.structural(e) {
            Ok(value) => Ok(value),
            Err(_) if !self.depends(e) => {
                // Whatever the failed attempt made opaque (`s` of `s.rest`) is part of `e` now.
                self.prologue.truncate(prologue);
                Ok(Value::Scalar(self.opaque(e.to_token_stream())))
            }
            Err(error) => Err(error),
        }
    }

    fn scalar(&mut self, e: &Expr) -> syn::Result<ExprId> {
        match self.expr(e)? {
            Value::Scalar(id) => Ok(id),
            _ => Err(self.error(e, "a vector where a number is expected")),
        }
    }

    fn opaque(&mut self, tokens: TokenStream) -> ExprId {
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
                    return Ok(binding.value.clone());
                }
                if self.time.as_ref().is_some_and(|t| *t == name) {
                    return Ok(Value::Scalar(self.opaque(p.to_token_stream())));
                }
                Err(self.error(p, format_args!("`{name}`")))
            }
            Expr::Field(f) => self.field(f),
            Expr::Index(index) => {
                let base = self.expr(&index.expr)?;
                let i = int_literal(&index.index).ok_or_else(|| {
                    self.error(&index.index, "an index that is not an integer literal")
                })?;
                self.component(&base, i, &index.index)
            }
            Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => {
                let value = self.expr(&u.expr)?;
                Ok(self.map(value, |g, x| g.neg(x)))
            }
            Expr::Binary(b) => self.binary(b),
            Expr::MethodCall(m) => self.method(m),
            Expr::Call(c) => self.call(c),
            Expr::Struct(s) => self.state_literal(s),
            Expr::Tuple(t) => Ok(Value::Tuple(
                t.elems
                    .iter()
                    .map(|e| self.expr(e))
                    .collect::<syn::Result<_>>()?,
            )),
            Expr::Array(a) => Ok(Value::Vector(
                a.elems
                    .iter()
                    .map(|e| self.scalar(e))
                    .collect::<syn::Result<_>>()?,
            )),
            Expr::Block(b) if b.label.is_none() => self.block(&b.block),
            Expr::If(i) => Err(self.error(&i.cond, "branching on the state (`if`)")),
            Expr::Match(m) => Err(self.error(&m.expr, "matching on the state (`match`)")),
            Expr::ForLoop(l) if self.depends(&l.expr) => {
                Err(self.error(&l.expr, "the state in a loop bound (`for`)"))
            }
            Expr::ForLoop(l) => Err(self.error(l.for_token, "a loop over the state (`for`)")),
            Expr::While(w) => Err(self.error(&w.cond, "the state in a loop condition (`while`)")),
            Expr::Loop(l) => Err(self.error(l.loop_token, "a `loop`")),
            Expr::Cast(c) => Err(self.error(c, "a cast (`as`) of a state-dependent value")),
            Expr::Macro(m) => Err(self.error(m, "a macro call on the state")),
            Expr::Closure(c) => Err(self.error(c, "a closure over the state")),
            Expr::Return(r) => Err(self.error(r, "`return`")),
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
                Some(shape) => Ok(Value::Vector(
                    (0..shape.len())
                        .map(|i| self.opaque(quote!(#f[#i])))
                        .collect(),
                )),
            };
        }
        let base = self.expr(&f.base)?;
        let index = match &f.member {
            Member::Named(n) => ["x", "y", "z", "w"].iter().position(|c| n == c),
            Member::Unnamed(i) => Some(i.index as usize),
        };
        let index =
            index.ok_or_else(|| self.error(&f.member, "a field other than `x`, `y`, `z`, `w`"))?;
        self.component(&base, index, &f.member)
    }

    fn component(&mut self, base: &Value, i: usize, at: impl ToTokens) -> syn::Result<Value> {
        match base {
            Value::Vector(v) if i < v.len() => Ok(Value::Scalar(v[i])),
            Value::Tuple(t) if i < t.len() => Ok(t[i].clone()),
            _ => Err(self.error(at, "a component that is out of range or of a number")),
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

    fn arithmetic(
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

    fn map(&mut self, value: Value, f: impl Fn(&mut Graph, ExprId) -> ExprId + Copy) -> Value {
        match value {
            Value::Scalar(x) => Value::Scalar(f(&mut self.graph, x)),
            Value::Vector(v) => {
                Value::Vector(v.into_iter().map(|x| f(&mut self.graph, x)).collect())
            }
            Value::Tuple(t) => Value::Tuple(t.into_iter().map(|v| self.map(v, f)).collect()),
        }
    }

    fn method(&mut self, m: &ExprMethodCall) -> syn::Result<Value> {
        let name = m.method.to_string();
        let receiver = self.expr(&m.receiver)?;
        let args: Vec<&Expr> = m.args.iter().collect();
        self.apply(&name, receiver, &args, &m.method)
    }

    /// `receiver.name(args)`, for a method call or its `f64::name(receiver, args)` form.
    fn apply(
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
                let f = match name {
                    "sqrt" => Func::Sqrt,
                    "exp" => Func::Exp,
                    "ln" => Func::Ln,
                    "sin" => Func::Sin,
                    "cos" => Func::Cos,
                    "tan" => Func::Tan,
                    "tanh" => Func::Tanh,
                    "abs" => Func::Abs,
                    "recip" => {
                        let one = self.graph.num(1.0);
                        return Ok(Value::Scalar(self.graph.div(one, x)));
                    }
                    _ => return Err(unsupported(self)),
                };
                Ok(Value::Scalar(self.graph.call(f, x)))
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
            (Value::Scalar(a), [b, c]) if name == "mul_add" => {
                let (b, c) = (self.scalar(b)?, self.scalar(c)?);
                let product = self.graph.mul(a, b);
                Ok(Value::Scalar(self.graph.add(product, c)))
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
            _ => Err(unsupported(self)),
        }
    }

    fn dot(&mut self, v: &[ExprId], w: &[ExprId]) -> ExprId {
        let mut sum = self.graph.num(0.0);
        for (&a, &b) in v.iter().zip(w) {
            let product = self.graph.mul(a, b);
            sum = self.graph.add(sum, product);
        }
        sum
    }

    fn call(&mut self, c: &syn::ExprCall) -> syn::Result<Value> {
        let Expr::Path(path) = &*c.func else {
            return Err(self.error(&c.func, "a call"));
        };
        let segments: Vec<String> = path
            .path
            .segments
            .iter()
            .map(|s| s.ident.to_string())
            .collect();
        let args: Vec<&Expr> = c.args.iter().collect();
        match segments
            .iter()
            .map(String::as_str)
            .collect::<Vec<_>>()
            .as_slice()
        {
            [.., ty, "new"] if vector_len(ty).is_some() || *ty == "SVector" => {
                let parts = args
                    .iter()
                    .map(|a| self.scalar(a))
                    .collect::<syn::Result<_>>()?;
                Ok(Value::Vector(parts))
            }
            [.., ty, "zeros"] if vector_len(ty).is_some() => {
                let zero = self.graph.num(0.0);
                Ok(Value::Vector(vec![zero; vector_len(ty).expect("checked")]))
            }
            [.., "f64", name] if !args.is_empty() => {
                let receiver = self.expr(args[0])?;
                let method = &path
                    .path
                    .segments
                    .last()
                    .expect("a path has segments")
                    .ident;
                self.apply(name, receiver, &args[1..], method)
            }
            _ => Err(self.error(
                &c.func,
                format_args!(
                    "a call of `{}` (odyn cannot see inside functions; inline it)",
                    segments.join("::")
                ),
            )),
        }
    }

    /// `<Model>State { x: …, v: … }`, the return value of `derivative`.
    fn state_literal(&mut self, s: &syn::ExprStruct) -> syn::Result<Value> {
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
    fn outputs(&mut self, value: Value, f: &syn::ImplItemFn) -> syn::Result<Vec<ExprId>> {
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

    fn integer(&self, e: &Expr) -> Option<i32> {
        match e {
            Expr::Lit(_) | Expr::Group(_) | Expr::Paren(_) => {
                int_literal(e).and_then(|n| i32::try_from(n).ok())
            }
            Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => self.integer(&u.expr).map(|n| -n),
            _ => None,
        }
    }

    fn offset(&self, name: &Ident) -> Option<usize> {
        let mut offset = 0;
        for f in &self.model.states {
            if f.ident == name {
                return Some(offset);
            }
            offset += f.shape.len();
        }
        None
    }

    fn state_value(&mut self, offset: usize, shape: Shape) -> Value {
        match shape {
            Shape::Scalar => Value::Scalar(self.graph.var(offset)),
            _ => Value::Vector(
                (0..shape.len())
                    .map(|i| self.graph.var(offset + i))
                    .collect(),
            ),
        }
    }

    fn parameter_shape(&self, name: &Ident) -> Option<Shape> {
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

#[derive(Clone, Copy)]
enum Arith {
    Add,
    Sub,
    Mul,
    Div,
}

fn compound(op: &BinOp) -> Option<Arith> {
    match op {
        BinOp::AddAssign(_) => Some(Arith::Add),
        BinOp::SubAssign(_) => Some(Arith::Sub),
        BinOp::MulAssign(_) => Some(Arith::Mul),
        BinOp::DivAssign(_) => Some(Arith::Div),
        _ => None,
    }
}

/// Finds reads of the state: `self.<state field>` or a local bound to a state-dependent value.
struct Depends<'l, 'm> {
    lowering: &'l Lowering<'m>,
    found: bool,
}

impl<'ast> Visit<'ast> for Depends<'_, '_> {
    fn visit_expr(&mut self, e: &'ast Expr) {
        if self.found {
            return;
        }
        match e {
            Expr::Field(f) if is_self(&f.base) => {
                if let Member::Named(name) = &f.member {
                    self.found |= self.lowering.model.field(name).is_some();
                }
            }
            Expr::Path(_) => {
                if let Some(name) = path_name(e) {
                    self.found |= self.lowering.lookup(&name).is_some_and(|b| b.dependent);
                }
            }
            _ => visit::visit_expr(self, e),
        }
    }

    fn visit_macro(&mut self, m: &'ast syn::Macro) {
        self.found |= self.lowering.depends_tokens(&m.tokens);
    }
}

fn is_self(e: &Expr) -> bool {
    matches!(e, Expr::Path(p) if p.qself.is_none() && p.path.is_ident("self"))
}

fn path_name(e: &Expr) -> Option<String> {
    match e {
        Expr::Path(p) if p.qself.is_none() => p.path.get_ident().map(Ident::to_string),
        _ => None,
    }
}

fn pattern_name(pat: &Pat) -> Option<String> {
    match pat {
        Pat::Ident(p) if p.subpat.is_none() => Some(p.ident.to_string()),
        Pat::Type(t) => pattern_name(&t.pat),
        _ => None,
    }
}

fn vector_len(ty: &str) -> Option<usize> {
    ty.strip_prefix("Vector")
        .and_then(|n| n.parse().ok())
        .filter(|n| (1..=6).contains(n))
}
