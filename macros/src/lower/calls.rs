//! Calls of paths: vector constructors (`Vector3::new`, `Vector3::zeros`), `f64::method(x, …)`,
//! and functions odyn cannot see inside, of one to four numbers, differentiated by central
//! differences of the call (IR `Extern`). Helper calls are [`super::inline`]'s.

use quote::ToTokens;
use syn::Expr;

use super::state::vector_len;
use super::{Lowering, Value};

impl Lowering<'_> {
    pub(super) fn call(&mut self, c: &syn::ExprCall) -> syn::Result<Value> {
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
            // A guarded loop's variable (`loops::guarded_for`): its value, typed like the end.
            ["odyn", "__private", "same_type"] if args.len() == 2 => self.expr(args[0]),
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
            _ if (1..=4).contains(&args.len()) => {
                // A function odyn cannot see into, of numbers: evaluated as written, its
                // derivative a central difference of the call (`Jacobian::EXACT` is then false).
                let mut lowered = Vec::with_capacity(args.len());
                for a in &args {
                    match self.expr(a)? {
                        Value::Scalar(id) => lowered.push(id),
                        _ => return Err(self.opaque_call_error(c, &segments)),
                    }
                }
                // State-free calls stay the user's code, as before (their value is opaque).
                if !lowered.iter().any(|&id| self.graph.reads_variables(id)) {
                    return Err(self.opaque_call_error(c, &segments));
                }
                let path = c.func.to_token_stream();
                Ok(Value::Scalar(self.graph.extern_call(path, &lowered)))
            }
            _ => Err(self.opaque_call_error(c, &segments)),
        }
    }

    /// The refusal of a call the graph cannot take as an extern: not one to four numbers in.
    fn opaque_call_error(&self, c: &syn::ExprCall, segments: &[String]) -> syn::Error {
        let name = segments.join("::");
        let last = segments.last().map_or("f", String::as_str);
        self.error(
            &c.func,
            format_args!(
                "a call of `{name}` with {} argument(s) not all numbers (odyn differentiates \
                 a function it cannot see inside by central differences only when it takes one \
                 to four `f64`s; mark it `#[odyn::function]` in the model's `#[system]` impl \
                 block and call it as `Self::{last}(…)`, or `self.{last}(…)` if it takes \
                 `&self`, for an exact Jacobian; or inline it)",
                c.args.len()
            ),
        )
    }
}
