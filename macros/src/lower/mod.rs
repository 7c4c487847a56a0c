//! Stage 4: lowering a force function's body from syn into the expression graph.
//!
//! Only what depends on the state must be understood: any sub-expression that does not (a
//! parameter, a call on parameters, a constant) becomes an opaque leaf, evaluated by the user's own
//! code before the Jacobian — the *prologue*. What does depend on the state must be built from the
//! supported operations ([`methods`]); anything else is an error at that sub-expression, naming
//! what is supported. The time is a variable of the graph, so ∂f/∂t comes from the same
//! differentiation as ∂f/∂y.
//!
//! The stage is split by construct:
//!
//! - this file: the entry points, the values a sub-expression lowers to, the error message;
//! - [`scope`]: locals, `let` patterns, and which expressions read the state or the time;
//! - [`names`]: what code names and may change, read from its syntax alone (assignment
//!   targets, the names a pattern binds, `return`s);
//! - [`statements`]: statements: `let`, assignments, state-free statements;
//! - [`branches`]: branches on parameters (`if`, `match`) and early `return`s from them;
//! - [`conditions`]: the conditions of an `if` on the state, as comparisons in the graph;
//! - [`expr`]: expressions — literals, paths, fields, operators, calls;
//! - [`state`]: reads of state fields, parameter shapes, the state literal and the function's
//!   value in state layout;
//! - [`methods`]: the one table of supported methods, with their rules and the list the error
//!   messages print;
//! - [`inline`]: calls of the model's helper functions ([`crate::helpers`]), lowered by lowering
//!   the helper's body in a scope of its own;
//! - [`loops`]: loops whose body reads the state, unrolled when odyn can count their iterations
//!   at compile time.

mod branches;
mod calls;
mod conditions;
mod expr;
mod guarded;
mod inline;
mod loops;
mod matches;
mod merge;
mod methods;
mod names;
mod scope;
mod state;
mod statements;

use std::collections::HashMap;

use proc_macro2::TokenStream;
use quote::ToTokens;
use syn::{Expr, Ident, Pat, Stmt};

use crate::helpers::Helpers;
use crate::ir::{ExprId, Graph};
use crate::model::Model;

use scope::Binding;

/// Deepest expression nesting the lowering follows; deeper code is refused with a compile error
/// rather than risking the compiler's stack (a 1000-deep expression once crashed rustc here).
pub(crate) const MAX_DEPTH: u32 = 128;

/// A lowered force function: made once per model, and copied for each derivative generated
/// from it (∂f/∂y with ∂f/∂t, ∂f/∂p), each of which adds its own nodes to its copy.
#[derive(Clone)]
pub(crate) struct Lowered {
    pub(crate) graph: Graph,
    /// f(t, y) component by component, in state layout order.
    pub(crate) outputs: Vec<ExprId>,
    /// What runs before the Jacobian: the body's state-independent statements, the opaque
    /// values, and copies of the branches on parameters, in source order.
    pub(crate) prologue: Vec<Prologue>,
    /// The graph variable of the time, when the function reads it.
    pub(crate) time: Option<usize>,
    /// Whether ∂f/∂t is exact: false when the time reaches f through code odyn cannot
    /// differentiate (a call of the user's own function of `t`, a loop).
    pub(crate) exact_time: bool,
}

/// One item of the prologue.
#[derive(Clone)]
pub(crate) enum Prologue {
    /// A state-independent statement of the user's, kept so opaque values can name its locals.
    Stmt(Box<Stmt>),
    /// Opaque value `index`, computed by the user's expression.
    Opaque(usize, TokenStream),
    /// A branch on parameters: the same branch runs in the prologue, records which arm it took in
    /// its selector, and computes the arm's own opaque values.
    Branch(Box<Branch>),
    /// The prologue of an inlined helper function: a block of its own, so its locals (and its
    /// parameters, bound at its top) stay its own and cannot shadow its caller's.
    Scope(Vec<Prologue>),
}

/// A branch of the prologue.
#[derive(Clone)]
pub(crate) struct Branch {
    /// The selector variable: set to the index of the arm that ran (none for
    /// [`BranchKind::Every`], whose arms all run).
    pub(crate) selector: u32,
    /// How the arm is chosen.
    pub(crate) kind: BranchKind,
    /// Each arm's prologue.
    pub(crate) arms: Vec<Vec<Prologue>>,
}

/// How a branch chooses its arm.
#[derive(Clone)]
pub(crate) enum BranchKind {
    /// `if c₀ {…} else if c₁ {…} else {…}`: the conditions, one fewer than the arms (the last
    /// arm is the `else`, empty when the user wrote none).
    If(Vec<Expr>),
    /// `match scrutinee { pattern [if guard] => … }`.
    Match(Box<Expr>, Vec<(Pat, Option<Expr>)>),
    /// The arms of a branch on the state, chosen in the graph: every arm's prologue runs, each
    /// in its own block (its `let`s stay its own), and no selector is set.
    Every,
}

/// The value of a sub-expression.
#[derive(Clone, Debug, PartialEq)]
enum Value {
    Scalar(ExprId),
    Vector(Vec<ExprId>),
    Tuple(Vec<Value>),
    /// An array of arrays or vectors (`[Vector3<f64>; 6]`, `[[f64; 2]; 3]`), row by row.
    Rows(Vec<Vec<ExprId>>),
}

struct Lowering<'m> {
    model: &'m Model<'m>,
    /// The model's helper functions, inlined where they are called.
    helpers: &'m Helpers,
    /// The function whose body is lowered, for the messages.
    function: String,
    /// The helpers being inlined, outermost first (the body lowered is the last one's).
    inlining: Vec<String>,
    /// The time argument's name and its graph variable.
    time: Option<(Ident, usize)>,
    /// Whether the time argument's name is in scope: not inside a helper, whose own names are
    /// its parameters.
    time_in_scope: bool,
    graph: Graph,
    prologue: Vec<Prologue>,
    opaques: usize,
    selectors: u32,
    scopes: Vec<HashMap<String, Binding>>,
    /// Current nesting of `expr` calls (see [`MAX_DEPTH`]).
    depth: u32,
    /// Set when an expression went deeper than [`MAX_DEPTH`].
    too_deep: bool,
    /// Set when the time reaches an opaque value (so ∂f/∂t cannot be exact).
    time_opaque: bool,
    /// Loop iterations unrolled so far (see [`loops`]).
    iterations: usize,
    /// Set when an index went past the end of a vector or array (see
    /// [`loops`]' loops bounded by parameters).
    past_end: bool,
    /// A particle or grid kernel (no `jacobian = finite_differences` or `dual` for those).
    kernel: bool,
    /// How many arms of branches chosen at run time (on parameters or on the state) enclose
    /// the code being lowered.
    arms: u32,
    /// Inside a loop bounded at run time: the arm depth of its iterations (see [`loops`]).
    guard: Option<u32>,
    /// The `for` loops bounded at run time whose iteration is being tried, outermost first
    /// (see [`guarded`]'s inner loops).
    trials: Vec<guarded::Trial>,
}

/// Lowers the body of `f`, the model's `acceleration` or `derivative`, inlining the `helpers` it
/// calls.
pub(crate) fn lower(
    model: &Model<'_>,
    helpers: &Helpers,
    f: &syn::ImplItemFn,
) -> syn::Result<Lowered> {
    let time = f.sig.inputs.iter().nth(1).and_then(|arg| match arg {
        syn::FnArg::Typed(t) => match &*t.pat {
            Pat::Ident(p) => Some((p.ident.clone(), model.len())),
            _ => None,
        },
        syn::FnArg::Receiver(_) => None,
    });
    let mut l = Lowering::new(model, helpers, f, time);
    let value = l.body(&f.block)?;
    let outputs = l.outputs(value, f)?;
    Ok(l.finish(outputs))
}

/// Lowers a kernel: a function of `inputs`, each `width` graph variables (input k binds the
/// variables width·k … width·k + width − 1; a scalar when `width` is 1, else a vector), whose value
/// is `outputs` numbers (a scalar when 1, else a vector or array). `model` supplies only parameter
/// shapes (its `states` are empty). Particle kernels take D-vectors and return a D-vector force;
/// a grid's `#[cell]` kernel takes its stencil reads as scalars and returns one value per field.
/// `time` names the kernel's time argument, if any: the variable after the inputs', so ∂f/∂t
/// comes from the same graph.
pub(crate) fn lower_kernel(
    model: &Model<'_>,
    helpers: &Helpers,
    f: &syn::ImplItemFn,
    inputs: &[Ident],
    width: usize,
    outputs: usize,
    time: Option<Ident>,
) -> syn::Result<Lowered> {
    let mut l = Lowering::new(model, helpers, f, time.map(|t| (t, inputs.len() * width)));
    l.kernel = true;
    for (k, name) in inputs.iter().enumerate() {
        let value = if width == 1 {
            Value::Scalar(l.graph.var(k))
        } else {
            Value::Vector((0..width).map(|i| l.graph.var(width * k + i)).collect())
        };
        l.bind(name.to_string(), Some(value), true);
    }
    let values = match l.body(&f.block)? {
        Value::Scalar(x) if outputs == 1 => vec![x],
        Value::Vector(v) if v.len() == outputs => v,
        _ => {
            let what = if outputs == 1 {
                "a number".to_string()
            } else {
                format!("{outputs} numbers")
            };
            return Err(l.error(
                &f.sig.output,
                format_args!("a kernel value that is not {what}"),
            ));
        }
    };
    Ok(l.finish(values))
}

impl<'m> Lowering<'m> {
    fn new(
        model: &'m Model<'m>,
        helpers: &'m Helpers,
        f: &syn::ImplItemFn,
        time: Option<(Ident, usize)>,
    ) -> Self {
        Lowering {
            model,
            helpers,
            function: f.sig.ident.to_string(),
            inlining: Vec::new(),
            time,
            time_in_scope: true,
            graph: Graph::default(),
            prologue: Vec::new(),
            opaques: 0,
            selectors: 0,
            scopes: vec![HashMap::new()],
            depth: 0,
            too_deep: false,
            time_opaque: false,
            iterations: 0,
            past_end: false,
            kernel: false,
            arms: 0,
            guard: None,
            trials: Vec::new(),
        }
    }

    fn finish(self, outputs: Vec<ExprId>) -> Lowered {
        Lowered {
            graph: self.graph,
            outputs,
            prologue: self.prologue,
            time: self.time.map(|(_, index)| index),
            exact_time: !self.time_opaque,
        }
    }

    /// Where the code lowered is, for the messages: `` `acceleration` ``, or inside a helper
    /// `` `restoring` (called by `acceleration`) ``.
    fn place(&self) -> String {
        match self.inlining.last() {
            None => format!("`{}`", self.function),
            Some(helper) => format!("`{helper}` (called by `{}`)", self.function),
        }
    }

    /// The error for something the differentiation cannot go through, at `tokens`.
    fn error(&self, tokens: impl ToTokens, what: impl std::fmt::Display) -> syn::Error {
        syn::Error::new_spanned(
            tokens,
            format!(
                "odyn cannot differentiate {what} in {}, so it cannot derive the Jacobian; {} \
                 (or add {}`jacobian = false` to `#[system]` to use explicit methods only)",
                self.place(),
                methods::supported(),
                if self.kernel {
                    ""
                } else {
                    "`jacobian = dual` (exact: automatic differentiation of the code as \
                     written, every function it passes the state to generic over the number \
                     type) or `jacobian = finite_differences` (central differences) to keep the \
                     implicit methods, or "
                }
            ),
        )
    }

    /// An error about the code's structure rather than an operation (a `return` in the wrong
    /// place), with its own advice.
    fn refuse(&self, tokens: impl ToTokens, message: impl std::fmt::Display) -> syn::Error {
        syn::Error::new_spanned(tokens, format!("{message} in {}", self.place()))
    }
}

/// The operator of `a op= b`.
fn compound(op: &syn::BinOp) -> Option<expr::Arith> {
    use expr::Arith;
    use syn::BinOp;
    match op {
        BinOp::AddAssign(_) => Some(Arith::Add),
        BinOp::SubAssign(_) => Some(Arith::Sub),
        BinOp::MulAssign(_) => Some(Arith::Mul),
        BinOp::DivAssign(_) => Some(Arith::Div),
        _ => None,
    }
}
