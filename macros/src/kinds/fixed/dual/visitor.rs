//! The `Dualize` visitor: rewrites a model's force and helpers to compute over `odyn::Dual`
//! (`f64` in types reads `Dual`, float literals and parameters are constants of it, `#[param]`
//! fields are seeded, helper calls go to their dual copies).

use proc_macro2::{Group, Span, TokenStream, TokenTree};
use quote::{ToTokens, format_ident, quote, quote_spanned};
use syn::visit_mut::{self, VisitMut};
use syn::{Expr, Ident, Lit, Member, Type};

use crate::helpers::Helpers;
use crate::model::{Model, Shape};

/// nalgebra's number traits, in scope in the dual copies: `x.floor()`, `x.max(y)`, `x.powi(2)`
/// of a dual number are theirs.
pub(super) const NUMBER_TRAITS: NumberTraits = NumberTraits;

/// See [`NUMBER_TRAITS`].
pub(super) struct NumberTraits;

impl ToTokens for NumberTraits {
    fn to_tokens(&self, tokens: &mut TokenStream) {
        tokens.extend(quote! {
            #[allow(unused_imports)]
            use ::odyn::__private::nalgebra::{ComplexField as _, RealField as _};
        });
    }
}

/// The name of the dual copy of function `name`.
pub(super) fn dual_name(name: &Ident) -> Ident {
    format_ident!("__odyn_dual_{}", name)
}

/// The model's fields that are not state, whatever their type: constants of the dual copies
/// (but for the `#[param]` one seeded).
fn constant_fields(model: &Model<'_>) -> Vec<(Ident, Type)> {
    model
        .item
        .fields
        .iter()
        .filter_map(|f| Some((f.ident.clone()?, f.ty.clone())))
        .filter(|(name, _)| model.field(name).is_none())
        .collect()
}

/// Rewrites the force's code to compute over `odyn::Dual`.
pub(super) struct Dualize {
    /// The fields that are not state, with their types ([`constant_fields`]).
    constants: Vec<(Ident, Type)>,
    helpers: Vec<String>,
    model: Ident,
    state: Ident,
    /// The first-order model's dual state type (`__<Model>StateDual`).
    pub(super) dual_state: Ident,
    /// The `#[param]` fields, in order: read as dual numbers seeded when their index is
    /// `parameter`'s value.
    seeded: Vec<String>,
    /// The dual copies' argument naming the `#[param]` seeded (`usize::MAX` for none).
    pub(super) parameter: Ident,
}

/// What a parameter place (`self.k`, `self.m[i]`, `self.g`) holds.
enum Holds {
    /// One number: read as a constant.
    Number,
    /// An array or a nalgebra vector of numbers: read as a map of constants.
    Numbers,
    /// Anything else: left as written.
    Other,
}

impl Dualize {
    pub(super) fn new(model: &Model<'_>, helpers: &Helpers, params: &[&Ident]) -> Dualize {
        Dualize {
            constants: constant_fields(model),
            helpers: helpers.names().collect(),
            model: model.ident().clone(),
            state: model.state_ident(),
            dual_state: format_ident!("__{}Dual", model.state_ident()),
            seeded: params.iter().map(ToString::to_string).collect(),
            parameter: format_ident!("__odyn_parameter", span = Span::mixed_site()),
        }
    }

    /// The type of a state field of `shape` over dual numbers.
    pub(super) fn field_type(&self, model: &Model<'_>, shape: Shape) -> TokenStream {
        self.tokens(model.type_of(shape))
    }

    /// The dual copy of helper `f`: its types and body over `Dual`, and the seeded parameter's
    /// index as its first argument after `self`.
    pub(super) fn helper(&mut self, f: &syn::ImplItemFn) -> TokenStream {
        let mut f = f.clone();
        f.attrs.retain(|a| !crate::syntax::is_function_attribute(a));
        f.sig.ident = dual_name(&f.sig.ident);
        self.visit_signature_mut(&mut f.sig);
        let parameter = &self.parameter;
        let at = usize::from(f.sig.receiver().is_some());
        f.sig
            .inputs
            .insert(at, syn::parse_quote!(#parameter: usize));
        self.visit_block_mut(&mut f.block);
        crate::math::route_block(&mut f.block);
        let statements = &f.block.stmts;
        f.block = syn::parse_quote!({ #NUMBER_TRAITS #(#statements)* });
        f.vis = syn::Visibility::Inherited;
        quote!(#[doc(hidden)] #[allow(clippy::all, unused_parens)] #f)
    }

    /// `tokens` (a type) with `f64` read as `Dual`, and the state type as its dual.
    pub(super) fn tokens(&self, tokens: TokenStream) -> TokenStream {
        tokens
            .into_iter()
            .map(|tree| match tree {
                TokenTree::Ident(ident) if ident == "f64" => {
                    let span = ident.span();
                    quote_spanned!(span=> ::odyn::Dual)
                }
                TokenTree::Ident(ident) if ident == self.state => {
                    let mut dual = self.dual_state.clone();
                    dual.set_span(ident.span());
                    dual.into_token_stream()
                }
                TokenTree::Group(group) => {
                    let mut inner = Group::new(group.delimiter(), self.tokens(group.stream()));
                    inner.set_span(group.span());
                    TokenTree::Group(inner).into_token_stream()
                }
                other => other.into_token_stream(),
            })
            .collect()
    }

    /// What the place `expr` holds when it is rooted at a parameter of the model.
    fn parameter_place(&self, expr: &Expr) -> Option<Holds> {
        let ty = self.place_type(expr)?;
        Some(holds(&ty))
    }

    /// The type of a place rooted at a parameter: `self.p`, then fields and indices.
    fn place_type(&self, expr: &Expr) -> Option<Type> {
        match expr {
            Expr::Field(f) if let Some(name) = self_field(f) => self
                .constants
                .iter()
                .find(|(p, _)| p == name)
                .map(|(_, ty)| ty.clone()),
            Expr::Field(f) => {
                let outer = self.place_type(&f.base)?;
                let Member::Named(name) = &f.member else {
                    return None;
                };
                let coordinate =
                    ["x", "y", "z", "w", "a", "b"].contains(&name.to_string().as_str());
                (coordinate && matches!(holds(&outer), Holds::Numbers))
                    .then(|| syn::parse_quote!(f64))
            }
            Expr::Index(i) => element(&self.place_type(&i.expr)?),
            Expr::Paren(p) => self.place_type(&p.expr),
            _ => None,
        }
    }

    /// The index of the `#[param]` field `self.<name>` reads, if it reads one.
    fn seeded_parameter(&self, f: &syn::ExprField) -> Option<usize> {
        let name = self_field(f)?;
        self.seeded.iter().position(|p| name == p)
    }

    /// Whether `func` names a helper: `Self::f` or `Model::f`.
    fn helper_path(&self, func: &Expr) -> bool {
        let Expr::Path(p) = func else { return false };
        let segments: Vec<_> = p.path.segments.iter().collect();
        matches!(segments.as_slice(), [ty, f]
            if (ty.ident == "Self" || ty.ident == self.model)
                && self.helpers.contains(&f.ident.to_string()))
    }

    /// Visits the index expressions of a parameter place, not the place itself.
    fn visit_indices(&mut self, expr: &mut Expr) {
        match expr {
            Expr::Index(i) => {
                self.visit_expr_mut(&mut i.index);
                self.visit_indices(&mut i.expr);
            }
            Expr::Field(f) => self.visit_indices(&mut f.base),
            Expr::Paren(p) => self.visit_indices(&mut p.expr),
            _ => {}
        }
    }
}

/// The field `self.<name>` reads, if `f` is such a read.
fn self_field(f: &syn::ExprField) -> Option<&Ident> {
    match &f.member {
        Member::Named(name) if crate::syntax::is_self(&f.base) => Some(name),
        _ => None,
    }
}

/// What a value of type `ty` holds.
fn holds(ty: &Type) -> Holds {
    if crate::syntax::is_f64(ty) {
        return Holds::Number;
    }
    match ty {
        Type::Array(a) if crate::syntax::is_f64(&a.elem) => Holds::Numbers,
        Type::Path(_) if crate::model::shape_of(ty).is_some() => Holds::Numbers,
        _ => Holds::Other,
    }
}

/// The element type of an indexed `ty`: an array's, a `Vec`'s, a nalgebra vector's (`f64`).
fn element(ty: &Type) -> Option<Type> {
    match ty {
        Type::Array(a) => Some((*a.elem).clone()),
        Type::Slice(s) => Some((*s.elem).clone()),
        Type::Reference(r) => element(&r.elem),
        Type::Path(p) => {
            let last = p.path.segments.last()?;
            if last.ident == "Vec" || last.ident == "Box" {
                if let syn::PathArguments::AngleBracketed(a) = &last.arguments
                    && let Some(syn::GenericArgument::Type(inner)) = a.args.first()
                {
                    return match inner {
                        Type::Slice(s) => Some((*s.elem).clone()),
                        other => Some(other.clone()),
                    };
                }
                return None;
            }
            crate::model::shape_of(ty).map(|_| syn::parse_quote!(f64))
        }
        _ => None,
    }
}

/// The primitive number types an `as` cast may name.
const PRIMITIVES: [&str; 13] = [
    "f32", "i8", "i16", "i32", "i64", "i128", "isize", "u8", "u16", "u32", "u64", "u128", "usize",
];

impl VisitMut for Dualize {
    fn visit_type_mut(&mut self, ty: &mut Type) {
        if let Ok(dual) = syn::parse2(self.tokens(ty.to_token_stream())) {
            *ty = dual;
        }
    }

    /// A path in an expression: the state type's name (`ForcedState { .. }`) reads as its dual.
    fn visit_path_mut(&mut self, path: &mut syn::Path) {
        for segment in &mut path.segments {
            if segment.ident == self.state {
                let span = segment.ident.span();
                segment.ident = self.dual_state.clone();
                segment.ident.set_span(span);
            }
        }
        visit_mut::visit_path_mut(self, path);
    }

    /// Items nested in the body (a `const`, a `fn`) keep their own types.
    fn visit_item_mut(&mut self, _: &mut syn::Item) {}

    /// Macros (`debug_assert!`) are left as written.
    fn visit_macro_mut(&mut self, _: &mut syn::Macro) {}

    fn visit_expr_mut(&mut self, expr: &mut Expr) {
        match expr {
            Expr::Lit(lit) if is_float(&lit.lit) => {
                let span = lit.lit.span();
                *expr = syn::parse_quote_spanned!(span=> ::odyn::Dual::constant(#lit));
            }
            Expr::Cast(cast) => {
                self.visit_expr_mut(&mut cast.expr);
                let (inner, ty) = (&cast.expr, &cast.ty);
                let span = cast.as_token.span;
                if crate::syntax::is_f64(ty) {
                    *expr = syn::parse_quote_spanned!(span=> ::odyn::__private::ToDual::to_dual(#inner));
                } else if PRIMITIVES.iter().any(|p| crate::syntax::is_plain(ty, p)) {
                    *expr = syn::parse_quote_spanned!(span=>
                        ::odyn::__private::DualCast::<#ty>::cast(#inner));
                } else {
                    self.visit_type_mut(&mut cast.ty);
                }
            }
            Expr::Path(p) if p.qself.is_none() && names_f64(&p.path) => {
                let constant = p
                    .path
                    .segments
                    .last()
                    .is_some_and(|s| s.ident.to_string().chars().all(|c| !c.is_lowercase()));
                if constant {
                    *expr = syn::parse_quote!(::odyn::Dual::constant(#p));
                } else if let Some(first) = p.path.segments.first_mut()
                    && first.ident == "f64"
                {
                    let span = first.ident.span();
                    first.ident = Ident::new("Dual", span);
                    let rest = &p.path;
                    *expr = syn::parse_quote_spanned!(span=> ::odyn::#rest);
                }
            }
            Expr::MethodCall(call)
                if crate::syntax::is_self(&call.receiver)
                    && self.helpers.contains(&call.method.to_string()) =>
            {
                call.method = dual_name(&call.method);
                for arg in &mut call.args {
                    self.visit_expr_mut(arg);
                }
                let parameter = &self.parameter;
                call.args.insert(0, syn::parse_quote!(#parameter));
            }
            Expr::Call(call) if self.helper_path(&call.func) => {
                if let Expr::Path(p) = &mut *call.func
                    && let Some(last) = p.path.segments.last_mut()
                {
                    last.ident = dual_name(&last.ident);
                }
                for arg in &mut call.args {
                    self.visit_expr_mut(arg);
                }
                let parameter = &self.parameter;
                call.args.insert(0, syn::parse_quote!(#parameter));
            }
            Expr::Field(f) if let Some(index) = self.seeded_parameter(f) => {
                let parameter = &self.parameter;
                *expr = syn::parse_quote!(::odyn::Dual::new(
                    #f,
                    if #parameter == #index { 1.0 } else { 0.0 },
                ));
            }
            Expr::Field(_) | Expr::Index(_) => match self.parameter_place(expr) {
                Some(Holds::Number) => {
                    self.visit_indices(expr);
                    *expr = syn::parse_quote!(::odyn::Dual::constant(#expr));
                }
                Some(Holds::Numbers) => {
                    self.visit_indices(expr);
                    *expr = syn::parse_quote!(#expr.map(::odyn::Dual::constant));
                }
                Some(Holds::Other) => self.visit_indices(expr),
                None => visit_mut::visit_expr_mut(self, expr),
            },
            _ => visit_mut::visit_expr_mut(self, expr),
        }
    }
}

/// Whether `lit` is a float literal (`2.0`, `1e-3`, `2f64`).
fn is_float(lit: &Lit) -> bool {
    match lit {
        Lit::Float(f) => f.suffix() != "f32",
        Lit::Int(i) => i.suffix() == "f64",
        _ => false,
    }
}

/// Whether `path` goes through the `f64` type or module: `f64::max`, `f64::consts::PI`,
/// `std::f64::consts::PI`.
fn names_f64(path: &syn::Path) -> bool {
    let mut segments = path.segments.iter().map(|s| s.ident.to_string());
    match segments.next().as_deref() {
        Some("f64") => path.segments.len() > 1,
        Some("std" | "core") => segments.next().as_deref() == Some("f64"),
        _ => false,
    }
}
