//! `#[param]` fields and ∂f/∂p: the derivative of the force with respect to each marked
//! parameter, from the same lowered graph as the Jacobian. A parameter read `self.k` is an
//! opaque value of the graph (one per read), so ∂f/∂k is the sum of the derivatives by each of
//! its reads ([`crate::derivative::Differentiator::derivative_by_opaque`]). A read the graph
//! does not see — inside an expression odyn keeps whole (a call of the user's own function), or
//! a statement it copies as written — is refused at its tokens: the derivative would miss it.

use proc_macro2::{Span, TokenStream, TokenTree};
use quote::{ToTokens, format_ident, quote};
use syn::{Attribute, Fields, ItemImpl, ItemStruct};

use super::functions::Function;
use super::jacobian::time_ident;
use super::layout::{component_tokens, inline_hint, state_args, state_params, time_param};
use crate::errors::Errors;
use crate::generate::{evaluation, hidden_fn, operand, time_copy};
use crate::ir::ExprId;
use crate::lower::{Lowered, Prologue};
use crate::model::{Model, Shape, shape_of};

/// The `#[param]` attribute on a field, if it has one.
pub(crate) fn param_attribute(attrs: &[Attribute]) -> Option<&Attribute> {
    attrs.iter().find(|a| a.path().is_ident("param"))
}

/// The `#[param]` fields of `item`, in declaration order; each must be a plain `f64` that is not
/// also state.
pub(super) fn parse<'a>(item: &'a ItemStruct, errors: &mut Errors) -> Vec<&'a syn::Ident> {
    let Fields::Named(named) = &item.fields else {
        return Vec::new();
    };
    let mut params = Vec::new();
    for field in &named.named {
        let Some(attr) = param_attribute(&field.attrs) else {
            continue;
        };
        let ident = field.ident.as_ref().expect("named fields have names");
        if let Some(role) = crate::model::Role::ATTRIBUTES
            .iter()
            .find(|(name, _)| field.attrs.iter().any(|a| a.path().is_ident(name)))
        {
            errors.at(
                attr,
                format_args!(
                    "`{ident}` is `#[{}]` state; `#[param]` marks a parameter (a field that is \
                     not state)",
                    role.0
                ),
            );
        } else if shape_of(&field.ty) != Some(Shape::Scalar) {
            errors.at(
                &field.ty,
                "a `#[param]` field must be an `f64`: ∂f/∂p is taken by scalar parameter",
            );
        } else {
            crate::syntax::no_arguments(attr, "`#[param]` takes no arguments", errors);
            params.push(ident);
        }
    }
    params
}

/// The `Parameters` impl of a model whose force is `lowered`: its parameter list, and ∂f/∂p as
/// straight-line code. Reports each read of a parameter the graph cannot see.
pub(super) fn parameters(
    model: &Model<'_>,
    params: &[&syn::Ident],
    lowered: Lowered,
    force: &Function,
    imp: &ItemImpl,
    errors: &mut Errors,
) -> TokenStream {
    let Lowered {
        mut graph,
        outputs,
        prologue,
        ..
    } = lowered;
    let names: Vec<String> = params.iter().map(ToString::to_string).collect();
    let mut reads = vec![Vec::new(); params.len()];
    find_reads(&prologue, &names, &mut reads, errors);
    if !errors.is_empty() {
        return TokenStream::new();
    }
    let mut differentiator = crate::derivative::Differentiator::default();
    let mut entries: Vec<(usize, usize, ExprId)> = Vec::new();
    for (row, &f) in outputs.iter().enumerate() {
        for (column, opaques) in reads.iter().enumerate() {
            let mut sum = graph.num(0.0);
            for &opaque in opaques {
                let d = differentiator.derivative_by_opaque(&mut graph, f, opaque);
                sum = graph.add(sum, d);
            }
            if !graph.is_zero(sum) {
                entries.push((row, column, sum));
            }
        }
    }
    let mut components = component_tokens(model);
    let (time_component, time_copy) = time_copy(time_ident(force));
    components.extend(time_component);
    let roots: Vec<ExprId> = entries.iter().map(|e| e.2).collect();
    let (prologue, lets) = evaluation(&graph, &roots, &components, &prologue);
    let out = format_ident!("__odyn_dfdp", span = Span::mixed_site());
    let stores = entries.iter().map(|&(row, column, d)| {
        let value = operand(&graph, d, &components);
        quote!(#out[(#row, #column)] = #value;)
    });
    let (n, p) = (model.len(), params.len());
    let receiver = &force.receiver;
    let time = time_param(force);
    let state_params = state_params(model);
    let hidden = hidden_fn(
        quote!(__odyn_parameter_jacobian(
            #receiver,
            #time,
            #(#state_params,)*
            #out: &mut ::odyn::__private::nalgebra::DMatrix<f64>
        )),
        inline_hint(model, quote!(#[inline])),
        &time_copy,
        &prologue,
        quote! {
            #(#lets)*
            if #out.shape() != (#n, #p) {
                *#out = ::odyn::__private::nalgebra::DMatrix::zeros(#n, #p);
            } else {
                #out.fill(0.0);
            }
            #(#stores)*
        },
    );
    let y = format_ident!("y");
    let args = state_args(model, &y);
    let doc = format!(
        "∂f/∂p for the parameters {}: {} structural non-zeros, derived by `#[system]` from the \
         model's code.",
        names.join(", "),
        entries.len()
    );
    let self_ty = &imp.self_ty;
    let values = parameters_trait(
        model,
        params,
        imp,
        &doc,
        quote!(self.__odyn_parameter_jacobian(t, #(#args,)* dfdp)),
    );
    quote! {
        #[automatically_derived]
        impl #self_ty {
            #hidden
        }
        #values
    }
}

/// The parameter struct `<Model>Parameters` and the `Parameters` impl of `model`, whose
/// `parameter_jacobian(&self, t, y, dfdp)` is `jacobian` (documented by `doc`).
pub(super) fn parameters_trait(
    model: &Model<'_>,
    params: &[&syn::Ident],
    imp: &ItemImpl,
    doc: &str,
    jacobian: TokenStream,
) -> TokenStream {
    let self_ty = &imp.self_ty;
    let (impl_generics, _, where_clause) = imp.generics.split_for_impl();
    let state = model.state_type();
    let names: Vec<String> = params.iter().map(ToString::to_string).collect();
    let indices = 0..params.len();
    let values = parameters_ident(model.ident());
    let vis = &model.item.vis;
    let struct_doc = format!(
        "The `#[param]` parameters of [`{}`] as one value (`Parameters::parameter_values`), \
         generated by `#[system]`.",
        model.ident()
    );
    let field_docs = names
        .iter()
        .map(|name| format!("`{}::{name}`.", model.ident()));
    quote! {
        #[doc = #struct_doc]
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        #vis struct #values {
            #(#[doc = #field_docs] pub #params: f64,)*
        }
        #[automatically_derived]
        impl #impl_generics ::odyn::Parameters for #self_ty #where_clause {
            type Values = #values;
            const NAMES: &'static [&'static str] = &[#(#names),*];
            fn parameter_values(&self) -> #values {
                #values { #(#params: self.#params),* }
            }
            fn set_parameter_values(&mut self, values: #values) {
                #(self.#params = values.#params;)*
            }
            fn parameters(&self) -> ::std::vec::Vec<f64> {
                ::std::vec![#(self.#params),*]
            }
            fn write_parameters(&mut self, values: &[f64]) {
                #(self.#params = values[#indices];)*
            }
            #[doc = #doc]
            fn parameter_jacobian(
                &self,
                t: f64,
                y: &#state,
                dfdp: &mut ::odyn::__private::nalgebra::DMatrix<f64>,
            ) {
                #jacobian
            }
        }
    }
}

/// The generated parameter struct of model `model`: `<Model>Parameters`.
fn parameters_ident(model: &syn::Ident) -> syn::Ident {
    format_ident!("{}Parameters", model)
}

/// The opaque values that are exactly a parameter (`self.k`), per parameter; every other place
/// a parameter reaches f without the graph seeing it is reported: an opaque expression that
/// reads it, or one that reads a local a statement kept as written computed from it.
fn find_reads(
    prologue: &[Prologue],
    names: &[String],
    reads: &mut [Vec<usize>],
    errors: &mut Errors,
) {
    let mut tainted = Vec::new();
    kept_locals(prologue, names, &mut tainted);
    opaque_reads(prologue, names, &tainted, reads, errors);
}

/// The locals bound by the prologue's statements kept as written that read a parameter, with
/// the parameter.
fn kept_locals(prologue: &[Prologue], names: &[String], out: &mut Vec<(String, String)>) {
    for item in prologue {
        match item {
            Prologue::Stmt(stmt) => {
                if let syn::Stmt::Local(local) = &**stmt
                    && let Some(init) = &local.init
                    && let Some(p) = read_parameter(init.expr.to_token_stream(), names)
                {
                    let pattern = local.pat.to_token_stream();
                    for name in identifiers(pattern) {
                        out.push((name, p.clone()));
                    }
                }
            }
            Prologue::Branch(branch) => {
                for arm in &branch.arms {
                    kept_locals(arm, names, out);
                }
            }
            Prologue::Scope(inner) => kept_locals(inner, names, out),
            Prologue::Opaque(..) => {}
        }
    }
}

fn opaque_reads(
    prologue: &[Prologue],
    names: &[String],
    tainted: &[(String, String)],
    reads: &mut [Vec<usize>],
    errors: &mut Errors,
) {
    for item in prologue {
        match item {
            Prologue::Opaque(index, tokens) => {
                if let Some(j) = names.iter().position(|p| is_read_of(tokens, p)) {
                    reads[j].push(*index);
                } else if let Some(p) = read_parameter(tokens.clone(), names) {
                    errors.at(
                        tokens,
                        format_args!(
                            "odyn cannot differentiate this with respect to the parameter `{p}`: \
                             it keeps the expression whole (a call of a function it cannot see \
                             into); compute with `self.{p}` where odyn can follow it, or drop \
                             `#[param]` from `{p}`"
                        ),
                    );
                } else if let Some((local, p)) = identifiers(tokens.clone())
                    .into_iter()
                    .find_map(|name| tainted.iter().find(|(l, _)| *l == name))
                {
                    errors.at(
                        tokens,
                        format_args!(
                            "odyn cannot differentiate this with respect to the parameter `{p}`: \
                             it reads `{local}`, computed from `self.{p}` by a statement odyn \
                             keeps as written; compute with `self.{p}` where odyn can follow it, \
                             or drop `#[param]` from `{p}`"
                        ),
                    );
                }
            }
            Prologue::Branch(branch) => {
                for arm in &branch.arms {
                    opaque_reads(arm, names, tainted, reads, errors);
                }
            }
            Prologue::Scope(inner) => opaque_reads(inner, names, tainted, reads, errors),
            Prologue::Stmt(_) => {}
        }
    }
}

/// Whether `tokens` are exactly `self.<name>`.
fn is_read_of(tokens: &TokenStream, name: &str) -> bool {
    let trees: Vec<TokenTree> = tokens.clone().into_iter().collect();
    matches!(
        trees.as_slice(),
        [TokenTree::Ident(s), TokenTree::Punct(dot), TokenTree::Ident(field)]
            if s == "self" && dot.as_char() == '.' && field == name
    )
}

/// Every identifier in `tokens`, groups included.
fn identifiers(tokens: TokenStream) -> Vec<String> {
    let mut out = Vec::new();
    for tree in tokens {
        match tree {
            TokenTree::Ident(i) => out.push(i.to_string()),
            TokenTree::Group(g) => out.extend(identifiers(g.stream())),
            _ => {}
        }
    }
    out
}

/// The first parameter of `names` that `tokens` read as `self.<name>`.
fn read_parameter(tokens: TokenStream, names: &[String]) -> Option<String> {
    let trees: Vec<TokenTree> = tokens.into_iter().collect();
    for (i, tree) in trees.iter().enumerate() {
        match tree {
            TokenTree::Ident(s) if s == "self" => {
                if let (Some(TokenTree::Punct(dot)), Some(TokenTree::Ident(name))) =
                    (trees.get(i + 1), trees.get(i + 2))
                    && dot.as_char() == '.'
                    && let Some(p) = names.iter().find(|p| name == *p)
                {
                    return Some(p.clone());
                }
            }
            TokenTree::Group(g) => {
                if let Some(p) = read_parameter(g.stream(), names) {
                    return Some(p);
                }
            }
            _ => {}
        }
    }
    None
}
