//! Stage 0: refuse input too deep to parse safely, before anything parses it.
//!
//! syn parses expressions recursively and odyn's stages walk them recursively, all on the
//! compiler's own thread: in a debug build about 4 KB of stack per level of parentheses and
//! 2 KB per operator chained at one level (measured). A 1000-deep expression overflowed the
//! stack and crashed rustc. This walk is iterative, so it is safe at any depth; past the limits
//! the user gets a compile error at the offending token instead.

use proc_macro2::{Delimiter, Span, TokenStream, TokenTree};

/// Deepest nesting of brackets accepted (parentheses, braces and square brackets together).
pub(crate) const MAX_NESTING: usize = 128;

/// Most operators accepted in one run (between commas or semicolons, at one level of brackets):
/// `a + b + c …` parses into a tree as deep as the run is long.
pub(crate) const MAX_CHAIN: usize = 512;

/// The first place `tokens` nests deeper or chains longer than the limits, with the message.
pub(crate) fn check(tokens: &TokenStream) -> Result<(), syn::Error> {
    let mut stack = vec![tokens.clone().into_iter()];
    let mut runs = vec![0usize];
    while let Some(iter) = stack.last_mut() {
        let Some(tree) = iter.next() else {
            stack.pop();
            runs.pop();
            continue;
        };
        match tree {
            TokenTree::Group(group) => {
                if stack.len() >= MAX_NESTING {
                    return Err(error(
                        group.span_open(),
                        format!(
                            "this code nests brackets more than {MAX_NESTING} levels deep; \
                             `#[system]` refuses it rather than risk the compiler's stack — split \
                             the expression with `let`s"
                        ),
                    ));
                }
                if group.delimiter() != Delimiter::None {
                    stack.push(group.stream().into_iter());
                    runs.push(0);
                } else {
                    stack.push(group.stream().into_iter());
                    runs.push(*runs.last().unwrap_or(&0));
                }
            }
            TokenTree::Punct(p) => {
                let run = runs.last_mut().expect("one run per level");
                if matches!(p.as_char(), ',' | ';') {
                    *run = 0;
                } else {
                    *run += 1;
                    if *run > MAX_CHAIN {
                        return Err(error(
                            p.span(),
                            format!(
                                "this expression chains more than {MAX_CHAIN} operators; \
                                 `#[system]` refuses it rather than risk the compiler's stack — \
                                 split it with `let`s"
                            ),
                        ));
                    }
                }
            }
            TokenTree::Ident(_) | TokenTree::Literal(_) => {}
        }
    }
    Ok(())
}

fn error(span: Span, message: String) -> syn::Error {
    syn::Error::new(span, message)
}

#[cfg(test)]
mod tests {
    use super::{MAX_CHAIN, MAX_NESTING, check};

    #[test]
    fn deep_and_long_input_is_refused_without_recursion() {
        let nested = |n: usize| format!("{}x{}", "(".repeat(n), ")".repeat(n));
        assert!(check(&nested(MAX_NESTING - 1).parse().unwrap()).is_ok());
        assert!(check(&nested(MAX_NESTING + 1).parse().unwrap()).is_err());
        // Far deeper than any recursive walk could go on a test thread's stack.
        assert!(check(&nested(100_000).parse().unwrap()).is_err());
        let chain = |n: usize| format!("x{}", " + 1.0".repeat(n));
        assert!(check(&chain(MAX_CHAIN).parse().unwrap()).is_ok());
        assert!(check(&chain(MAX_CHAIN + 1).parse().unwrap()).is_err());
        // Commas separate runs: a long array is fine.
        let array = format!("[{}]", vec!["-1.0"; 10 * MAX_CHAIN].join(", "));
        assert!(check(&array.parse().unwrap()).is_ok());
    }
}
