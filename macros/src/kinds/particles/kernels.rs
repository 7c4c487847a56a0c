//! The impl block of a particle model: its `#[pair(links)]` and `#[particle]` kernels and its
//! potential.

use quote::ToTokens;
use syn::{Attribute, FnArg, Ident, ImplItem, ImplItemFn, ItemImpl, Pat, ReturnType, Type};

use super::Particles;
use crate::errors::Errors;
use crate::model::{Len, Shape, shape_of};
use crate::syntax::{attribute, is_plain, is_ref_self, no_arguments, vec_element};

/// Which elements a kernel runs over.
pub(super) enum Over {
    /// `#[pair(field)]`: the links in `self.field`.
    Pairs(Ident),
    /// `#[particle]`: every particle.
    Particles,
}

/// One force kernel.
pub(super) struct Kernel {
    pub(super) over: Over,
    pub(super) f: ImplItemFn,
    /// `#[particle]` kernels: whether the first argument is the particle index.
    pub(super) index: bool,
    /// The vector arguments: positions, then velocities when the kernel takes them.
    pub(super) vectors: Vec<Ident>,
}

impl Kernel {
    pub(super) fn reads_velocity(&self) -> bool {
        let positions = match self.over {
            Over::Pairs(_) => 2,
            Over::Particles => 1,
        };
        self.vectors.len() > positions
    }
}

/// The impl block's kernels and potential.
pub(super) struct Functions {
    pub(super) kernels: Vec<Kernel>,
    pub(super) potential: Option<(ImplItemFn, syn::Block)>,
}

fn kernel_attribute(f: &ImplItemFn) -> Option<&Attribute> {
    attribute(&f.attrs, &["pair", "particle"])
}

pub(super) fn parse_kernels(
    imp: &ItemImpl,
    particles: &Particles<'_>,
    helpers: &crate::helpers::Helpers,
    errors: &mut Errors,
) -> Functions {
    let mut functions = Functions {
        kernels: Vec::new(),
        potential: None,
    };
    let rewriter_model = particles.rewriter_model();
    for member in &imp.items {
        let ImplItem::Fn(f) = member else { continue };
        let name = &f.sig.ident;
        if let Some(attr) = kernel_attribute(f) {
            if let Some(kernel) = parse_kernel(f, attr, particles, errors) {
                let (_, reads) = crate::rewrite::rewrite(
                    &f.block,
                    &rewriter_model,
                    helpers,
                    name,
                    false,
                    errors,
                );
                if let Some(tokens) = reads.values().next() {
                    errors.at(
                        tokens,
                        format_args!(
                            "kernel `{name}` reads the particles only through its arguments, \
                             not through `self`"
                        ),
                    );
                } else {
                    functions.kernels.push(kernel);
                }
            }
        } else if name == "potential" {
            check_receiver_only(f, errors);
            let (body, _) =
                crate::rewrite::rewrite(&f.block, &rewriter_model, helpers, name, false, errors);
            functions.potential = Some((f.clone(), body));
        } else if ["acceleration", "derivative", "energy"].contains(&name.to_string().as_str()) {
            errors.at(
                name,
                format_args!(
                    "`{name}` is for fixed-size models; particle model `{}` writes its forces as \
                     kernels (`#[pair(links)]`, `#[particle]`) and its potential energy as \
                     `fn potential(&self) -> f64` (odyn adds the kinetic energy)",
                    particles.item.ident
                ),
            );
        }
    }
    if functions.kernels.is_empty() && errors.is_empty() {
        errors.at(
            &imp.self_ty,
            format_args!(
                "particle model `{}` has no force kernels; mark a method `#[pair(links)]` (a \
                 force between the two particles of each link in `self.links`) or `#[particle]` \
                 (a force on every particle)",
                particles.item.ident
            ),
        );
    }
    functions
}

fn check_receiver_only(f: &ImplItemFn, errors: &mut Errors) {
    let mut inputs = f.sig.inputs.iter();
    match inputs.next() {
        Some(FnArg::Receiver(r)) if is_ref_self(r) => {}
        _ => errors.at(&f.sig, "`potential` must take `&self`"),
    }
    if let Some(extra) = inputs.next() {
        errors.at(extra, "`potential` takes only `&self`");
    }
    if !matches!(&f.sig.output, ReturnType::Type(_, ty) if is_plain(ty, "f64")) {
        errors.at(&f.sig, "`potential` must return `f64`");
    }
}

fn parse_kernel(
    f: &ImplItemFn,
    attr: &Attribute,
    particles: &Particles<'_>,
    errors: &mut Errors,
) -> Option<Kernel> {
    let name = &f.sig.ident;
    let before = errors.len();
    let over = if attr.path().is_ident("pair") {
        match attr.parse_args::<Ident>() {
            Ok(field) => {
                // The runtime reads the links as a `Vec`; say so here rather than in
                // generated code.
                let declared = particles
                    .item
                    .fields
                    .iter()
                    .find(|f| f.ident.as_ref() == Some(&field));
                match declared {
                    Some(f) if vec_element(&f.ty).is_some() => {}
                    Some(f) => errors.at(
                        &f.ty,
                        format_args!(
                            "`{field}` holds the links of `#[pair({field})]`, so it must be a \
                             `Vec` of a type implementing `odyn::particles::Link` (such as \
                             `Vec<Spring>`)"
                        ),
                    ),
                    None => errors.at(
                        &field,
                        format_args!(
                            "`{}` has no field `{field}` to take the links from",
                            particles.item.ident
                        ),
                    ),
                }
                Over::Pairs(field)
            }
            Err(_) => {
                errors.at(
                    attr,
                    "`#[pair]` names the field holding the links: `#[pair(springs)]`",
                );
                return None;
            }
        }
    } else {
        no_arguments(attr, "`#[particle]` takes no arguments", errors);
        Over::Particles
    };
    if !f.sig.generics.params.is_empty() {
        errors.at(
            &f.sig.generics,
            format_args!("kernel `{name}` cannot be generic"),
        );
    }
    let mut inputs = f.sig.inputs.iter().peekable();
    match inputs.next() {
        Some(FnArg::Receiver(r)) if is_ref_self(r) => {}
        _ => errors.at(
            &f.sig,
            format_args!("kernel `{name}` must take `&self` first"),
        ),
    }
    let mut index = false;
    match &over {
        Over::Pairs(_) => match inputs.next() {
            Some(FnArg::Typed(t)) if matches!(&*t.ty, Type::Reference(_)) => {}
            other => errors.at(
                other.map_or_else(|| f.sig.to_token_stream(), ToTokens::to_token_stream),
                format_args!(
                    "a `#[pair]` kernel takes `&self`, the link (`link: &Spring`), then the two \
                     particles' positions (and optionally their velocities): \
                     `fn {name}(&self, link: &Spring, xa: Vector{0}<f64>, xb: Vector{0}<f64>, \
                     va: Vector{0}<f64>, vb: Vector{0}<f64>)`",
                    particles.dim
                ),
            ),
        },
        Over::Particles => {
            if let Some(FnArg::Typed(t)) = inputs.peek()
                && is_plain(&t.ty, "usize")
            {
                index = true;
                inputs.next();
            }
        }
    }
    let mut vectors = Vec::new();
    for input in inputs {
        let FnArg::Typed(t) = input else { continue };
        let is_vector =
            matches!(shape_of(&t.ty), Some(Shape::Vector(d)) if d == Len::Known(particles.dim));
        match (&*t.pat, is_vector) {
            (Pat::Ident(p), true) if p.subpat.is_none() => vectors.push(p.ident.clone()),
            _ => errors.at(
                input,
                format_args!(
                    "a kernel's particle arguments are plain names of type `Vector{}<f64>`",
                    particles.dim
                ),
            ),
        }
    }
    let allowed: &[usize] = match over {
        Over::Pairs(_) => &[2, 4],
        Over::Particles => &[1, 2],
    };
    if errors.len() == before && !allowed.contains(&vectors.len()) {
        errors.at(
            &f.sig.inputs,
            format_args!(
                "kernel `{name}` takes {} vectors: the position{s} and optionally the velocit{ies}",
                allowed
                    .iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join(" or "),
                s = if allowed[0] == 2 { "s" } else { "" },
                ies = if allowed[0] == 2 { "ies" } else { "y" },
            ),
        );
    }
    if !matches!(&f.sig.output, ReturnType::Type(_, ty)
        if matches!(shape_of(ty), Some(Shape::Vector(d)) if d == Len::Known(particles.dim)))
    {
        errors.at(
            &f.sig,
            format_args!(
                "kernel `{name}` must return the force as `Vector{}<f64>`",
                particles.dim
            ),
        );
    }
    (errors.len() == before).then(|| Kernel {
        over,
        f: f.clone(),
        index,
        vectors,
    })
}
