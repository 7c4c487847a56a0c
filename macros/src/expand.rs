//! Wires the stages together for the two places `#[system]` goes.
//!
//! On the struct, the expansion generates the typed state and defines a `macro_rules!` carrying
//! the struct's tokens. On the impl block, the expansion calls that macro, which hands struct and
//! impl together to [`system_impl`]: the one place that sees both the fields and the function
//! bodies. So the struct must come before its impl block, in the same module.

use proc_macro2::TokenStream;
use quote::{ToTokens, quote};
use syn::parse::{Parse, ParseStream};
use syn::{Item, ItemImpl, ItemStruct, Type};

use crate::errors::{Errors, with_error};
use crate::generate::never_run;
use crate::syntax::strip_method_attributes;
use crate::{args, generate, kinds};

/// `#[system(...)]` on an item.
pub(crate) fn system(args: TokenStream, item: TokenStream) -> TokenStream {
    if let Err(error) = crate::limits::check(&item) {
        return too_deep(item, error);
    }
    match syn::parse2::<Item>(item.clone()) {
        Ok(Item::Struct(s)) => kinds::expand_struct(args, &s),
        Ok(Item::Impl(i)) => forward_impl(args, &i),
        Ok(other) => {
            let message = "`#[system]` goes on a model struct and on that struct's `impl` block";
            let error = match &other {
                Item::Enum(e) => syn::Error::new_spanned(&e.ident, message),
                Item::Fn(f) => syn::Error::new_spanned(&f.sig.ident, message),
                Item::Union(u) => syn::Error::new_spanned(&u.ident, message),
                Item::Trait(t) => syn::Error::new_spanned(&t.ident, message),
                _ => syn::Error::new_spanned(&other, message),
            };
            with_error(other, error)
        }
        Err(error) => with_error(item, error),
    }
}

/// `#[odyn::function]` where `#[system]` did not read it (it removes the attribute from the
/// methods of the impl block it reads): the item unchanged, and the error saying where a helper
/// goes.
pub(crate) fn function(args: TokenStream, item: TokenStream) -> TokenStream {
    let name = match syn::parse2::<syn::ItemFn>(item.clone()) {
        Ok(f) => f.sig.ident,
        Err(error) => return with_error(item, error),
    };
    let message = format!(
        "`#[odyn::function]` marks a helper of a model, read by `#[system]`: move `{name}` into \
         the model's `#[system]` impl block (taking `&self` to read parameters, or no receiver) \
         and call it as `self.{name}(…)` or `Self::{name}(…)`"
    );
    let error = if args.is_empty() {
        syn::Error::new(name.span(), message)
    } else {
        syn::Error::new_spanned(args, "`#[odyn::function]` takes no arguments")
    };
    with_error(item, error)
}

/// The impl half: hand the impl block to the macro the struct's expansion defined.
fn forward_impl(args: TokenStream, item: &ItemImpl) -> TokenStream {
    let mut errors = Errors::default();
    if !args.is_empty() {
        errors.at(
            &args,
            "`#[system]` on an impl block takes no arguments; put `integrator` and `dt` on the struct",
        );
    }
    if let Some((_, path, _)) = &item.trait_ {
        errors.at(
            path,
            "`#[system]` goes on the model's own `impl` block, not on a trait impl",
        );
    }
    let model = match &*item.self_ty {
        // `impl<const N: usize> Chain<N>` too: the struct's expansion knows whether it is
        // generic.
        Type::Path(p) if p.qself.is_none() && p.path.segments.len() == 1 => {
            Some(&p.path.segments[0].ident)
        }
        _ => None,
    };
    if model.is_none() {
        errors.at(
            &item.self_ty,
            "expected the model struct's name, such as `impl Spring`",
        );
    }
    // Whatever becomes of the block, it was marked: the struct's check is satisfied.
    let marked = model.map(|_| {
        let (impl_generics, _, where_clause) = item.generics.split_for_impl();
        let self_ty = &item.self_ty;
        quote!(impl #impl_generics ::odyn::__private::SystemImpl for #self_ty #where_clause {})
    });
    match (errors.finish(), model) {
        (Ok(()), Some(model)) => {
            let forwarder = generate::forwarder_name(model);
            quote!(#forwarder! { #item } #marked)
        }
        (result, _) => {
            let error = result.err().unwrap_or_else(|| {
                syn::Error::new_spanned(&item.self_ty, "`#[system]` rejected this impl block")
            });
            let expanded = with_error(item, error);
            quote!(#expanded #marked)
        }
    }
}

/// The input of `__system_impl!`: `[args] struct … impl …`.
struct Forwarded {
    args: TokenStream,
    item: ItemStruct,
    imp: ItemImpl,
}

impl Parse for Forwarded {
    fn parse(input: ParseStream<'_>) -> syn::Result<Self> {
        let content;
        syn::bracketed!(content in input);
        Ok(Forwarded {
            args: content.parse()?,
            item: input.parse()?,
            imp: input.parse()?,
        })
    }
}

/// The input of `__system_impl!` for a rejected struct: `! impl …`; holds the impl block with
/// odyn's method attributes removed and its bodies replaced by ones that never run.
struct Rejected(ItemImpl);

impl Parse for Rejected {
    fn parse(input: ParseStream<'_>) -> syn::Result<Self> {
        input.parse::<syn::Token![!]>()?;
        Ok(Rejected(never_run(
            strip_method_attributes(&input.parse()?, &kinds::method_attributes()),
            |_| true,
        )))
    }
}

/// Struct and impl together: the runtime trait impls.
pub(crate) fn system_impl(input: TokenStream) -> TokenStream {
    if let Err(error) = crate::limits::check(&input) {
        return error.to_compile_error();
    }
    if let Ok(rejected) = syn::parse2::<Rejected>(input.clone()) {
        return rejected.0.into_token_stream();
    }
    let Forwarded { args, item, imp } = match syn::parse2(input) {
        Ok(forwarded) => forwarded,
        Err(error) => return error.to_compile_error(),
    };
    let mut errors = Errors::default();
    let args = args::parse(args, &mut errors);
    let expanded = kinds::expand_impl(&args, &item, &imp);
    // The struct's expansion parsed these same tokens and was accepted, so this parse finds no
    // problem; were it to find one, it is reported rather than dropped.
    let error = errors.finish().err().map(|e| e.to_compile_error());
    quote!(#expanded #error)
}

/// Input too deep to parse: the error, and the item unchanged (rustc parses it, on a stack that
/// grows as it needs). For a model's impl block (`impl Name { … }`, read from its first tokens
/// without parsing the rest) a stub `Model` impl too, so call sites draw no follow-on errors.
fn too_deep(item: TokenStream, error: syn::Error) -> TokenStream {
    let error = error.to_compile_error();
    let mut tokens = item.clone().into_iter();
    let stub = match (tokens.next(), tokens.next(), tokens.next()) {
        (
            Some(proc_macro2::TokenTree::Ident(keyword)),
            Some(proc_macro2::TokenTree::Ident(model)),
            Some(proc_macro2::TokenTree::Group(_)),
        ) if keyword == "impl" => {
            let state = crate::model::state_ident(&model);
            let stub = generate::stub_model(&model, &state);
            quote!(#stub impl ::odyn::__private::SystemImpl for #model {})
        }
        _ => TokenStream::new(),
    };
    quote!(#item #error #stub)
}

#[cfg(test)]
mod tests {
    use proc_macro2::TokenStream;
    use quote::quote;

    /// Checks the pretty-printed expansion of `input` against `tests/snapshots/<name>.rs`;
    /// `ODYN_BLESS=1 cargo test -p odyn-macros` rewrites the snapshots after a reviewed change.
    fn snapshot(name: &str, input: TokenStream) {
        let expanded = super::system_impl(input);
        let file: syn::File =
            syn::parse2(expanded.clone()).unwrap_or_else(|e| panic!("{e}: {expanded}"));
        let pretty = prettyplease::unparse(&file);
        assert!(!pretty.contains("compile_error"), "{pretty}");
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/snapshots")
            .join(format!("{name}.rs"));
        if std::env::var_os("ODYN_BLESS").is_some() {
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(&path, &pretty).unwrap();
        }
        let expected = std::fs::read_to_string(&path).unwrap_or_default();
        assert_eq!(
            pretty, expected,
            "expansion of `{name}` changed; review, then bless with ODYN_BLESS=1"
        );
    }

    /// `#[odyn::function]` where `#[system]` did not read it: the item as written and one error
    /// naming it, on a free function and on a method of another impl block alike.
    #[test]
    fn a_misplaced_helper_attribute_is_one_error_beside_the_item() {
        for item in [
            quote!(
                fn cubic(x: f64) -> f64 {
                    x * x * x
                }
            ),
            quote!(
                pub fn cubic(&self, x: f64) -> f64 {
                    self.k * x * x * x
                }
            ),
        ] {
            let expanded = super::function(TokenStream::new(), item.clone()).to_string();
            assert!(expanded.starts_with(&item.to_string()), "{expanded}");
            assert_eq!(expanded.matches("compile_error").count(), 1, "{expanded}");
            assert!(expanded.contains("move `cubic` into"), "{expanded}");
        }
    }

    #[test]
    fn grid_expansion() {
        snapshot(
            "heat",
            quote! {
                [integrator = ImplicitEuler, dt = 0.001]
                pub struct Heat {
                    #[field] pub u: Grid,
                    pub d: f64, pub dx: f64,
                }
                impl Heat {
                    #[cell]
                    fn conduction(&self, u: Stencil) -> f64 { self.d * u.laplacian() / (self.dx * self.dx) }
                }
            },
        );
    }

    #[test]
    fn spring_expansion() {
        snapshot(
            "spring",
            quote! {
                [integrator = SymplecticEuler, dt = 0.016]
                pub struct Spring {
                    #[position] pub x: f64, #[velocity] pub v: f64,
                    pub k: f64, pub b: f64, pub m: f64,
                }
                impl Spring {
                    fn acceleration(&self) -> f64 { (-self.k * self.x - self.b * self.v) / self.m }
                    fn energy(&self) -> f64 { 0.5 * self.m * self.v * self.v + 0.5 * self.k * self.x * self.x }
                }
            },
        );
    }

    /// A model with `#[param]`s: its Jacobian and its ∂f/∂p come from the one lowering of the
    /// force (a copy each).
    #[test]
    fn parameters_expansion() {
        snapshot(
            "parameters",
            quote! {
                [integrator = Rodas5P]
                pub struct Decay {
                    #[state] pub y: f64, #[state] pub z: f64,
                    #[param] pub k: f64, #[param] pub c: f64,
                }
                impl Decay {
                    fn derivative(&self, t: f64) -> DecayState {
                        let rate = if self.c > 0.0 { self.k * self.y } else { self.k };
                        DecayState { y: -rate + (self.c * t).sin(), z: rate - self.c * self.z * self.z }
                    }
                }
            },
        );
    }

    #[test]
    fn generic_expansion() {
        snapshot(
            "generic",
            quote! {
                []
                pub struct Chain<const N: usize> {
                    #[position] pub x: [f64; N], #[velocity] pub v: [f64; N], pub k: f64,
                }
                impl<const N: usize> Chain<N> {
                    fn acceleration(&self) -> [f64; N] {
                        let mut a = [0.0; N];
                        for i in 1..N { a[i] = -self.k * (self.x[i] - self.x[i - 1]); }
                        a
                    }
                }
            },
        );
    }

    /// A first-order model (its dual state struct), a helper's dual copy, a table read as
    /// constants and a cast to an index, under `jacobian = dual`.
    #[test]
    fn dual_expansion() {
        snapshot(
            "dual",
            quote! {
                [jacobian = dual]
                pub struct Tabled {
                    #[state] pub x: f64, #[state] pub y: [f64; 2], pub table: [f64; 4], pub k: f64,
                }
                impl Tabled {
                    fn derivative(&self, t: f64) -> TabledState {
                        let i = (self.x.abs() * 2.0).min(2.0) as usize;
                        TabledState { x: self.table[i] * self.y[0] + t, y: Self::pair(self.k, self.x) }
                    }
                    #[odyn::function]
                    fn pair(k: f64, x: f64) -> [f64; 2] { [-k * x, f64::max(x, 0.0)] }
                }
            },
        );
    }

    #[test]
    fn lorenz_expansion() {
        snapshot(
            "lorenz",
            quote! {
                []
                pub struct Lorenz {
                    #[state] pub x: f64, #[state] pub y: f64, #[state] pub z: f64,
                    pub sigma: f64, pub rho: f64, pub beta: f64,
                }
                impl Lorenz {
                    fn derivative(&self) -> LorenzState {
                        LorenzState {
                            x: self.sigma * (self.y - self.x),
                            y: self.x * (self.rho - self.z) - self.y,
                            z: self.x * self.y - self.beta * self.z,
                        }
                    }
                }
            },
        );
    }

    /// Helpers inlined: `restoring`'s parameter-only `let` and the state-free argument of
    /// `drag` run in a block of their own before the Jacobian; the Jacobian is the inlined one.
    #[test]
    fn helper_expansion() {
        snapshot(
            "duffing",
            quote! {
                [integrator = Rodas5P]
                pub struct Duffing {
                    #[position] pub x: f64, #[velocity] pub v: f64,
                    pub k: f64, pub c: f64, pub b: f64,
                }
                impl Duffing {
                    fn acceleration(&self) -> f64 { self.restoring(self.x) + Self::drag(self.b, self.v) }
                    #[odyn::function]
                    fn restoring(&self, x: f64) -> f64 { let k = self.k * 2.0; -k * x - self.c * x.powi(3) }
                    #[odyn::function]
                    fn drag(b: f64, v: f64) -> f64 { -b * v * v.abs() }
                }
            },
        );
    }

    #[test]
    fn kepler_expansion() {
        snapshot(
            "kepler",
            quote! {
                [integrator = Leapfrog]
                pub struct Kepler {
                    #[position] pub r: Vector2<f64>, #[velocity] pub v: Vector2<f64>, pub gm: f64,
                }
                impl Kepler {
                    fn acceleration(&self) -> Vector2<f64> {
                        let r = self.r;
                        -self.gm * r / r.norm().powi(3)
                    }
                }
            },
        );
    }
    #[test]
    fn pleiades_expansion() {
        snapshot(
            "pleiades",
            quote! {
                [jacobian = false]
                pub struct Pleiades {
                    #[position] pub x: [f64; 7], #[position] pub y: [f64; 7],
                    #[velocity] pub u: [f64; 7], #[velocity] pub v: [f64; 7],
                    pub m: [f64; 7],
                }
                impl Pleiades {
                    fn acceleration(&self) -> ([f64; 7], [f64; 7]) {
                        let mut ax = [0.0; 7];
                        let mut ay = [0.0; 7];
                        for i in 0..7 {
                            for j in (i + 1)..7 {
                                let dx = self.x[j] - self.x[i];
                                let dy = self.y[j] - self.y[i];
                                let r2 = dx * dx + dy * dy;
                                let w = 1.0 / (r2 * r2.sqrt());
                                ax[i] += self.m[j] * w * dx;
                                ay[i] += self.m[j] * w * dy;
                                ax[j] -= self.m[i] * w * dx;
                                ay[j] -= self.m[i] * w * dy;
                            }
                        }
                        (ax, ay)
                    }
                }
            },
        );
    }
}
