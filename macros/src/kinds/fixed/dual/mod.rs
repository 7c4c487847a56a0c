//! `#[system(jacobian = dual)]`: the Jacobian by forward-mode automatic differentiation of the
//! model's own code, for code the lowering cannot read (loops to a const parameter `N`, calls of
//! functions generic over the number type) but which computes with numbers Rust can make dual.
//!
//! The force is emitted a second time over `odyn::Dual` (runtime `model/dual/`): `f64` in its
//! types reads `Dual`, a float literal, a parameter (`self.k`, `self.m[i]`, `self.g` as a
//! vector) and an `as f64` cast are constants of it, and `as usize` of a dual number casts its
//! value. Each Jacobian column j is one call of that copy at the state with component j seeded
//! (its derivative one); ∂f/∂t is one call with the time seeded. The `#[odyn::function]` helpers
//! it calls get dual copies too; any other function it passes the state to must be generic over
//! the number type (`fn f<T: RealField>(x: T) -> T`), or the copy does not compile: rustc's
//! "expected `f64`, found `Dual`" then names the call and the function.

mod visitor;

use proc_macro2::{Span, TokenStream};
use quote::{ToTokens, quote, quote_spanned};
use syn::visit_mut::VisitMut;
use syn::{Ident, ItemImpl};

use self::visitor::{Dualize, NUMBER_TRAITS, dual_name};
use super::functions::Function;
use super::layout::{SMALL, inline_hint};
use crate::generate::time_independent;
use crate::helpers::Helpers;
use crate::model::{Model, Order, Role, Shape};
use crate::rewrite::state_local;

/// The dual copies of a model's functions, the dual state of a first-order model, and its
/// `Jacobian` (and `Parameters`) impls.
pub(crate) fn jacobian(
    model: &Model<'_>,
    force: &Function,
    helpers: &Helpers,
    params: &[&Ident],
    imp: &ItemImpl,
) -> TokenStream {
    let mut dualize = Dualize::new(model, helpers, params);
    let rows = Rows::of(model, &dualize);
    let state = dual_state(model, &dualize);
    let copies = copies(model, force, helpers, imp, &mut dualize);
    let jacobian = jacobian_impl(model, imp, &rows, force.time.is_some());
    let parameters = parameters_impl(model, params, imp, &rows);
    quote_spanned! {Span::call_site()=>
        #state
        #copies
        #jacobian
        #parameters
    }
}

/// Where the dual copy's output goes in f: after a second-order model's position rows (whose
/// derivative is the velocity, so their rows of ∂f/∂y are an identity block and of ∂f/∂t and
/// ∂f/∂p zero), from the first row of a first-order one.
struct Rows {
    /// The first row of the output, an expression (`positions` or `0`).
    first: TokenStream,
    /// The statement defining `positions`, for a second-order model.
    positions: TokenStream,
}

impl Rows {
    fn of(model: &Model<'_>, dualize: &Dualize) -> Rows {
        match model.order {
            Order::First => Rows {
                first: quote!(0),
                positions: TokenStream::new(),
            },
            Order::Second => {
                let lens = model.with_role(Role::Position).map(|f| {
                    let ty = dualize.field_type(model, f.shape);
                    quote!(+ <#ty as ::odyn::__private::Seeded>::LEN)
                });
                Rows {
                    first: quote!(positions),
                    positions: quote!(let positions: usize = 0 #(#lens)*;),
                }
            }
        }
    }
}

/// A first-order model's state over dual numbers (`__<Model>StateDual`), which its function's
/// dual copy builds where the function builds its state, and whose derivatives are a column.
fn dual_state(model: &Model<'_>, dualize: &Dualize) -> Option<TokenStream> {
    (model.order == Order::First).then(|| {
        let name = &dualize.dual_state;
        let generics = &model.item.generics;
        let (_, type_generics, _) = generics.split_for_impl();
        let idents: Vec<_> = model.states.iter().map(|f| f.ident).collect();
        let types = model
            .states
            .iter()
            .map(|f| dualize.field_type(model, f.shape));
        quote! {
            #[doc(hidden)]
            #[allow(non_camel_case_types)]
            struct #name #generics {
                #(#idents: #types,)*
            }
            #[automatically_derived]
            impl #generics ::odyn::__private::Tangent for #name #type_generics {
                #[inline(always)]
                fn tangent(&self, out: &mut impl FnMut(f64)) {
                    #(::odyn::__private::Tangent::tangent(&self.#idents, out);)*
                }
            }
        }
    })
}

/// The hidden methods: the force's dual copy, `__odyn_dual_at` (the copy at a flat state with
/// one component or parameter seeded), and the helpers' dual copies.
fn copies(
    model: &Model<'_>,
    force: &Function,
    helpers: &Helpers,
    imp: &ItemImpl,
    dualize: &mut Dualize,
) -> TokenStream {
    let self_ty = &imp.self_ty;
    let (impl_generics, _, where_clause) = imp.generics.split_for_impl();
    let parameter = dualize.parameter.clone();
    // The state fields as arguments, in layout order, seeded from the flat state.
    let fields: Vec<_> = model
        .states
        .iter()
        .map(|f| {
            let ty = dualize.field_type(model, f.shape);
            (state_local(f.ident), ty, f.shape == Shape::Scalar)
        })
        .collect();
    let seeds = fields.iter().map(|(local, ty, _)| {
        quote! {
            let #local = <#ty as ::odyn::__private::Seeded>::seeded(
                &values[offset..], seed.wrapping_sub(offset));
            offset += <#ty as ::odyn::__private::Seeded>::LEN;
        }
    });
    let args = fields.iter().map(|(local, _, scalar)| match scalar {
        true => quote!(#local),
        false => quote!(&#local),
    });
    let inputs = fields.iter().map(|(local, ty, scalar)| match scalar {
        true => quote!(#local: #ty),
        false => quote!(#local: &#ty),
    });
    let output = dualize.tokens(force.output.to_token_stream());
    let receiver = &force.receiver;
    let time = match &force.time {
        Some(t) => {
            let (pat, ty) = (&t.pat, dualize.tokens(t.ty.to_token_stream()));
            quote!(#pat: #ty)
        }
        None => quote!(_: ::odyn::Dual),
    };
    let mut body = force.body.clone();
    dualize.visit_block_mut(&mut body);
    let helpers: Vec<_> = helpers.iter().map(|h| dualize.helper(&h.f)).collect();
    let force_fn = dual_name(&force.name);
    let inline = inline_hint(model, quote!(#[inline]));
    quote! {
        #[automatically_derived]
        impl #impl_generics #self_ty #where_clause {
            #[doc(hidden)]
            #inline
            #[allow(unused_variables, unused_assignments, unused_parens, non_snake_case, clippy::all)]
            fn #force_fn(#receiver, #parameter: usize, #time, #(#inputs),*) -> #output {
                #NUMBER_TRAITS
                #body
            }
            /// f over dual numbers at the state `values`, component `seed` of the state or
            /// `#[param]` number `parameter` seeded.
            #[doc(hidden)]
            #inline
            #[allow(unused_assignments, clippy::all)]
            fn __odyn_dual_at(
                &self,
                t: ::odyn::Dual,
                values: &[f64],
                seed: usize,
                parameter: usize,
            ) -> #output {
                let mut offset = 0usize;
                #(#seeds)*
                self.#force_fn(parameter, t, #(#args),*)
            }
            #(#helpers)*
        }
    }
}

/// The `Jacobian` impl: ∂f/∂y column by column, and ∂f/∂t when f reads the time.
fn jacobian_impl(model: &Model<'_>, imp: &ItemImpl, rows: &Rows, reads_time: bool) -> TokenStream {
    let self_ty = &imp.self_ty;
    let (impl_generics, _, where_clause) = imp.generics.split_for_impl();
    let state = model.state_type();
    let Rows { first, positions } = rows;
    let (matrix, store, zeros) = if !model.is_generic() && model.len() <= SMALL {
        let n = model.len_tokens();
        (
            quote!(::odyn::__private::nalgebra::SMatrix<f64, #n, #n>),
            quote!(jacobian[(row, column)] = value),
            quote!(::odyn::__private::nalgebra::SMatrix::<f64, #n, #n>::zeros()),
        )
    } else {
        (
            quote!(::odyn::FaerDense),
            quote!(jacobian.set(row, column, value)),
            quote!(::odyn::FaerDense::zeros(
                ::odyn::State::as_slice(state).len()
            )),
        )
    };
    let time = if reads_time {
        quote! {
            /// True: the model's function reads the time; ∂f/∂t by one dual evaluation.
            const TIME_DEPENDENT: bool = true;
            fn time_derivative(&self, t: f64, y: &#state, dfdt: &mut #state) {
                let out = self.__odyn_dual_at(
                    ::odyn::Dual::new(t, 1.0),
                    ::odyn::State::as_slice(y),
                    usize::MAX,
                    usize::MAX,
                );
                let dfdt = ::odyn::State::as_mut_slice(dfdt);
                #positions
                let mut row = #first;
                dfdt[..row].fill(0.0);
                ::odyn::__private::Tangent::tangent(&out, &mut |value| {
                    dfdt[row] = value;
                    row += 1;
                });
            }
        }
    } else {
        time_independent(&state, "The model's function does not read the time")
    };
    quote! {
        #[automatically_derived]
        impl #impl_generics ::odyn::Jacobian for #self_ty #where_clause {
            type Matrix = #matrix;
            /// Not known: the Jacobian is taken by forward-mode differentiation of the code.
            const NONZEROS: &'static [(usize, usize)] = &[];
            #[inline]
            fn jacobian_matrix(&self, state: &#state) -> #matrix {
                #zeros
            }
            /// ∂f/∂y column by column, one dual evaluation of f each, exact to rounding.
            fn jacobian(&self, t: f64, y: &#state, jacobian: &mut #matrix) {
                let values = ::odyn::State::as_slice(y);
                let time = ::odyn::Dual::constant(t);
                #positions
                for column in 0..values.len() {
                    let out = self.__odyn_dual_at(time, values, column, usize::MAX);
                    // A second-order model's position rows: d(position)/dt = velocity.
                    let start = #first;
                    for row in 0..start {
                        let value = if column == start + row { 1.0 } else { 0.0 };
                        #store;
                    }
                    let mut row = start;
                    ::odyn::__private::Tangent::tangent(&out, &mut |value| {
                        #store;
                        row += 1;
                    });
                }
            }
            #time
        }
    }
}

/// The `Parameters` impl of a model with `#[param]`s: ∂f/∂p column by column, one dual
/// evaluation of f per parameter.
fn parameters_impl(
    model: &Model<'_>,
    params: &[&Ident],
    imp: &ItemImpl,
    rows: &Rows,
) -> Option<TokenStream> {
    if params.is_empty() {
        return None;
    }
    let count = params.len();
    let names: Vec<String> = params.iter().map(ToString::to_string).collect();
    let doc = format!(
        "∂f/∂p for the parameters {}: by dual numbers, one evaluation of f per parameter.",
        names.join(", ")
    );
    let Rows { first, positions } = rows;
    Some(super::parameters::parameters_trait(
        model,
        params,
        imp,
        &doc,
        quote! {
            let values = ::odyn::State::as_slice(y);
            if dfdp.shape() != (values.len(), #count) {
                *dfdp = ::odyn::__private::nalgebra::DMatrix::zeros(values.len(), #count);
            }
            let time = ::odyn::Dual::constant(t);
            #positions
            for column in 0..#count {
                let out = self.__odyn_dual_at(time, values, usize::MAX, column);
                let start = #first;
                for row in 0..start {
                    dfdp[(row, column)] = 0.0;
                }
                let mut row = start;
                ::odyn::__private::Tangent::tangent(&out, &mut |value| {
                    dfdp[(row, column)] = value;
                    row += 1;
                });
            }
        },
    ))
}
