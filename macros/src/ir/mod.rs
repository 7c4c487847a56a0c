//! Stage 5a: the expression graph the force function is lowered to and differentiated in.
//!
//! A flat arena: an [`ExprId`] indexes a [`Node`] whose children were created before it, so the
//! arena order is a valid evaluation order. Nodes are hash-consed — building the same node twice
//! returns the same id — so common subexpressions are shared for free, and the smart
//! constructors fold constants and the identities 0 + x, 1·x, 0·x, −(−x), x¹, x⁰. This stage is
//! pure: no syn, no quote.
//!
//! The functions a node may call, with their values and derivatives, are in `functions.rs`.

mod functions;

use std::collections::HashMap;

pub(crate) use functions::{Func, Func2};

/// An index into a [`Graph`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub(crate) struct ExprId(u32);

impl ExprId {
    pub(crate) fn index(self) -> usize {
        self.0 as usize
    }
}

/// One node of the graph.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub(crate) enum Node {
    /// A constant, by its bits (so it can be hashed); −0 is stored as +0.
    Const(u64),
    /// Variable `k`: a state component (what the Jacobian differentiates by), or the time.
    Var(usize),
    /// A state-independent value computed by user code (a parameter, a call), by index.
    Opaque(usize),
    Add(ExprId, ExprId),
    Mul(ExprId, ExprId),
    Div(ExprId, ExprId),
    Neg(ExprId),
    Powi(ExprId, i32),
    /// xʸ with a state-independent y.
    Powf(ExprId, ExprId),
    Call(Func, ExprId),
    Call2(Func2, ExprId, ExprId),
    /// `if selector == arm { then } else { otherwise }`: which arm of a branch on parameters ran
    /// (the selector is set by the prologue's copy of the branch).
    Select {
        selector: u32,
        arm: u32,
        then: ExprId,
        otherwise: ExprId,
    },
    /// `if a <= b { then } else { otherwise }`, comparing values of the graph: `min`, `max` and
    /// `clamp` of state-dependent values.
    Pick {
        a: ExprId,
        b: ExprId,
        then: ExprId,
        otherwise: ExprId,
    },
    /// A call of a function odyn cannot see into (a crate's, or the user's own unmarked one),
    /// `function(args[..arity])`, of numbers returning a number: evaluated as written.
    Extern {
        function: u32,
        args: [ExprId; 4],
        arity: u8,
    },
    /// ∂/∂args[wrt] of an [`Node::Extern`] call, by a central difference of the call itself:
    /// (f(…, a + h, …) − f(…, a − h, …)) / ((a + h) − (a − h)), h = ε^⅓·max(|a|, 1).
    Slope {
        function: u32,
        args: [ExprId; 4],
        arity: u8,
        wrt: u8,
    },
}

impl Node {
    /// The nodes this one reads, in a fixed order (at most four).
    pub(crate) fn children(self) -> impl Iterator<Item = ExprId> {
        let (list, len): ([ExprId; 4], usize) = match self {
            Node::Const(_) | Node::Var(_) | Node::Opaque(_) => ([ExprId(0); 4], 0),
            Node::Extern { args, arity, .. } | Node::Slope { args, arity, .. } => {
                (args, usize::from(arity))
            }
            Node::Neg(a) | Node::Powi(a, _) | Node::Call(_, a) => ([a, a, a, a], 1),
            Node::Add(a, b)
            | Node::Mul(a, b)
            | Node::Div(a, b)
            | Node::Powf(a, b)
            | Node::Call2(_, a, b) => ([a, b, b, b], 2),
            Node::Select {
                then, otherwise, ..
            } => ([then, otherwise, otherwise, otherwise], 2),
            Node::Pick {
                a,
                b,
                then,
                otherwise,
            } => ([a, b, then, otherwise], 4),
        };
        list.into_iter().take(len)
    }
}

/// The arena.
#[derive(Clone, Default, Debug)]
pub(crate) struct Graph {
    nodes: Vec<Node>,
    index: HashMap<Node, ExprId>,
    /// The functions of [`Node::Extern`] calls, as the user wrote their paths.
    externs: Vec<proc_macro2::TokenStream>,
}

impl Graph {
    pub(crate) fn node(&self, id: ExprId) -> Node {
        self.nodes[id.index()]
    }

    #[cfg(test)]
    pub(crate) fn len(&self) -> usize {
        self.nodes.len()
    }

    /// The value of a constant node.
    pub(crate) fn constant(&self, id: ExprId) -> Option<f64> {
        match self.node(id) {
            Node::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    pub(crate) fn is_zero(&self, id: ExprId) -> bool {
        self.constant(id) == Some(0.0)
    }

    fn intern(&mut self, node: Node) -> ExprId {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = ExprId(u32::try_from(self.nodes.len()).expect("fewer than 2³² nodes"));
        self.nodes.push(node);
        self.index.insert(node, id);
        id
    }

    pub(crate) fn num(&mut self, value: f64) -> ExprId {
        let value = if value == 0.0 { 0.0 } else { value };
        self.intern(Node::Const(value.to_bits()))
    }

    pub(crate) fn var(&mut self, component: usize) -> ExprId {
        self.intern(Node::Var(component))
    }

    pub(crate) fn opaque(&mut self, index: usize) -> ExprId {
        self.intern(Node::Opaque(index))
    }

    /// The call `path(args)` of a function the graph cannot see into (1 to 4 arguments; the
    /// caller checks).
    pub(crate) fn extern_call(
        &mut self,
        path: proc_macro2::TokenStream,
        args: &[ExprId],
    ) -> ExprId {
        let key = path.to_string();
        let function = match self.externs.iter().position(|p| p.to_string() == key) {
            Some(i) => i,
            None => {
                self.externs.push(path);
                self.externs.len() - 1
            }
        };
        let mut padded = [ExprId(0); 4];
        padded[..args.len()].copy_from_slice(args);
        self.intern(Node::Extern {
            function: u32::try_from(function).expect("fewer than 2³² functions"),
            args: padded,
            arity: u8::try_from(args.len()).expect("at most four arguments"),
        })
    }

    /// ∂/∂(argument `wrt`) of the extern call `call` (a [`Node::Extern`]).
    pub(crate) fn slope(&mut self, call: ExprId, wrt: u8) -> ExprId {
        match self.node(call) {
            Node::Extern {
                function,
                args,
                arity,
            } => self.intern(Node::Slope {
                function,
                args,
                arity,
                wrt,
            }),
            _ => self.num(f64::NAN),
        }
    }

    /// The path of extern function `function`, as written.
    pub(crate) fn extern_path(&self, function: u32) -> &proc_macro2::TokenStream {
        &self.externs[function as usize]
    }

    /// Whether `id` reads a variable (a state component or the time).
    pub(crate) fn reads_variables(&self, id: ExprId) -> bool {
        self.reachable([id])
            .into_iter()
            .any(|i| matches!(self.node(i), Node::Var(_)))
    }

    /// Whether the graph calls a function it cannot see into: its derivatives then hold
    /// central differences of those calls.
    pub(crate) fn has_externs(&self) -> bool {
        !self.externs.is_empty()
    }

    pub(crate) fn add(&mut self, a: ExprId, b: ExprId) -> ExprId {
        match (self.constant(a), self.constant(b)) {
            (Some(x), Some(y)) => self.num(x + y),
            (Some(0.0), _) => b,
            (_, Some(0.0)) => a,
            _ => {
                // x + (−y) stays as written; order the operands so a + b and b + a share a node.
                let (a, b) = if a <= b { (a, b) } else { (b, a) };
                self.intern(Node::Add(a, b))
            }
        }
    }

    pub(crate) fn sub(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let minus_b = self.neg(b);
        self.add(a, minus_b)
    }

    pub(crate) fn mul(&mut self, a: ExprId, b: ExprId) -> ExprId {
        match (self.constant(a), self.constant(b)) {
            (Some(x), Some(y)) => self.num(x * y),
            (Some(0.0), _) | (_, Some(0.0)) => self.num(0.0),
            (Some(1.0), _) => b,
            (_, Some(1.0)) => a,
            (Some(-1.0), _) => self.neg(b),
            (_, Some(-1.0)) => self.neg(a),
            _ => {
                let (a, b) = if a <= b { (a, b) } else { (b, a) };
                self.intern(Node::Mul(a, b))
            }
        }
    }

    pub(crate) fn div(&mut self, a: ExprId, b: ExprId) -> ExprId {
        match (self.constant(a), self.constant(b)) {
            (Some(x), Some(y)) => self.num(x / y),
            (Some(0.0), _) => self.num(0.0),
            (_, Some(1.0)) => a,
            (_, Some(-1.0)) => self.neg(a),
            _ => self.intern(Node::Div(a, b)),
        }
    }

    pub(crate) fn neg(&mut self, a: ExprId) -> ExprId {
        match self.node(a) {
            Node::Const(bits) => self.num(-f64::from_bits(bits)),
            Node::Neg(inner) => inner,
            _ => self.intern(Node::Neg(a)),
        }
    }

    pub(crate) fn powi(&mut self, a: ExprId, n: i32) -> ExprId {
        match (n, self.constant(a)) {
            (0, _) => self.num(1.0),
            (1, _) => a,
            (_, Some(x)) => self.num(x.powi(n)),
            _ => self.intern(Node::Powi(a, n)),
        }
    }

    pub(crate) fn powf(&mut self, a: ExprId, b: ExprId) -> ExprId {
        match (self.constant(a), self.constant(b)) {
            (Some(x), Some(y)) => self.num(libm::pow(x, y)),
            (_, Some(1.0)) => a,
            (_, Some(0.0)) => self.num(1.0),
            (_, Some(y)) if y.fract() == 0.0 && y.abs() <= 64.0 => self.powi(a, y as i32),
            _ => self.intern(Node::Powf(a, b)),
        }
    }

    pub(crate) fn call(&mut self, f: Func, a: ExprId) -> ExprId {
        match self.constant(a) {
            Some(x) => self.num(f.eval(x)),
            None => self.intern(Node::Call(f, a)),
        }
    }

    pub(crate) fn call2(&mut self, f: Func2, a: ExprId, b: ExprId) -> ExprId {
        match (self.constant(a), self.constant(b)) {
            (Some(x), Some(y)) => self.num(f.eval(x, y)),
            _ => self.intern(Node::Call2(f, a, b)),
        }
    }

    /// `if selector == arm { then } else { otherwise }`; one value when both agree.
    pub(crate) fn select(
        &mut self,
        selector: u32,
        arm: u32,
        then: ExprId,
        otherwise: ExprId,
    ) -> ExprId {
        if then == otherwise {
            then
        } else {
            self.intern(Node::Select {
                selector,
                arm,
                then,
                otherwise,
            })
        }
    }

    /// `if a <= b { then } else { otherwise }`; one value when both agree.
    pub(crate) fn pick(&mut self, a: ExprId, b: ExprId, then: ExprId, otherwise: ExprId) -> ExprId {
        if then == otherwise {
            return then;
        }
        match (self.constant(a), self.constant(b)) {
            (Some(x), Some(y)) => {
                if x <= y {
                    then
                } else {
                    otherwise
                }
            }
            _ => self.intern(Node::Pick {
                a,
                b,
                then,
                otherwise,
            }),
        }
    }

    /// The ids reachable from `roots`, in arena (evaluation) order.
    pub(crate) fn reachable(&self, roots: impl IntoIterator<Item = ExprId>) -> Vec<ExprId> {
        let mut seen = vec![false; self.nodes.len()];
        let mut stack: Vec<ExprId> = roots.into_iter().collect();
        while let Some(id) = stack.pop() {
            if std::mem::replace(&mut seen[id.index()], true) {
                continue;
            }
            stack.extend(self.node(id).children());
        }
        (0..self.nodes.len())
            .filter(|&i| seen[i])
            .map(|i| ExprId(i as u32))
            .collect()
    }

    /// Evaluates `id` with state `vars` and opaque values `opaques`, every selector 0 (for tests).
    #[cfg(test)]
    pub(crate) fn eval(&self, id: ExprId, vars: &[f64], opaques: &[f64]) -> f64 {
        let e = |id| self.eval(id, vars, opaques);
        match self.node(id) {
            Node::Const(bits) => f64::from_bits(bits),
            Node::Var(k) => vars[k],
            Node::Opaque(i) => opaques[i],
            Node::Add(a, b) => e(a) + e(b),
            Node::Mul(a, b) => e(a) * e(b),
            Node::Div(a, b) => e(a) / e(b),
            Node::Neg(a) => -e(a),
            Node::Powi(a, n) => e(a).powi(n),
            Node::Powf(a, b) => libm::pow(e(a), e(b)),
            Node::Call(f, a) => f.eval(e(a)),
            Node::Call2(f, a, b) => f.eval(e(a), e(b)),
            Node::Select {
                arm,
                then,
                otherwise,
                ..
            } => e(if arm == 0 { then } else { otherwise }),
            Node::Pick {
                a,
                b,
                then,
                otherwise,
            } => e(if e(a) <= e(b) { then } else { otherwise }),
            // The user's functions are not evaluated at compile time.
            Node::Extern { .. } | Node::Slope { .. } => f64::NAN,
        }
    }
}
