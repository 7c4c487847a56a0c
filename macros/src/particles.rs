//! Particle models: `Vec<VectorD<f64>>` positions and velocities, forces as per-element kernels.
//!
//! The same pipeline as fixed-size models, per kernel: the struct gives the particle fields
//! ([`parse_struct`]); the impl block gives the kernels ([`parse_kernels`]); each kernel body is
//! lowered with its vector arguments as the variables ([`lower::lower_kernel`]) and
//! differentiated into D×D blocks; [`generate`] emits the blocks as straight-line code and the
//! runtime trait impls, which leave the loops over particles and links to `odyn::particles`.

use proc_macro2::{Span, TokenStream};
use quote::{ToTokens, format_ident, quote};
use syn::{
    Attribute, FnArg, GenericArgument, Ident, ImplItem, ImplItemFn, ItemImpl, ItemStruct, Pat,
    PathArguments, ReturnType, Type,
};

use crate::args::Args;
use crate::errors::Errors;
use crate::generate::{operand, prologue_tokens, straight_line};
use crate::ir::ExprId;
use crate::lower::{self, Lowered};
use crate::model::{Model, Order, Role, Shape, StateField, shape_of};

/// The attributes that mark a particle model's fields.
const FIELD_ATTRIBUTES: [&str; 4] = ["position", "velocity", "mass", "pinned"];

/// A particle model's struct.
pub(crate) struct Particles<'a> {
    pub(crate) item: &'a ItemStruct,
    /// Spatial dimension D (2 or 3).
    pub(crate) dim: usize,
    pub(crate) position: &'a Ident,
    pub(crate) velocity: &'a Ident,
    pub(crate) mass: &'a Ident,
    pub(crate) pinned: Option<&'a Ident>,
}

impl Particles<'_> {
    fn state_ident(&self) -> Ident {
        format_ident!("{}State", self.item.ident)
    }

    /// The model as the body rewriter sees it: positions and velocities are state.
    fn rewriter_model(&self) -> Model<'_> {
        let field = |ident, role| StateField {
            ident,
            role,
            shape: Shape::Vector(self.dim),
        };
        Model {
            item: self.item,
            order: Order::Second,
            states: vec![
                field(self.position, Role::Position),
                field(self.velocity, Role::Velocity),
            ],
        }
    }

    /// The model as a kernel's lowering sees it: every field a parameter.
    fn parameter_model(&self) -> Model<'_> {
        Model {
            item: self.item,
            order: Order::Second,
            states: Vec::new(),
        }
    }

    fn vector_type(&self) -> TokenStream {
        let d = proc_macro2::Literal::usize_unsuffixed(self.dim);
        quote!(::odyn::__private::nalgebra::SVector<f64, #d>)
    }
}

/// Whether `item` is a particle model: a `Vec` position or velocity, or a `#[mass]`/`#[pinned]`
/// field.
pub(crate) fn is_particle_model(item: &ItemStruct) -> bool {
    item.fields.iter().any(|f| {
        f.attrs.iter().any(|a| {
            a.path().is_ident("mass")
                || a.path().is_ident("pinned")
                || ((a.path().is_ident("position") || a.path().is_ident("velocity"))
                    && vec_element(&f.ty).is_some())
        })
    })
}

/// `T` of `Vec<T>`.
fn vec_element(ty: &Type) -> Option<&Type> {
    let Type::Path(p) = ty else { return None };
    let last = p.path.segments.last()?;
    if last.ident != "Vec" {
        return None;
    }
    let PathArguments::AngleBracketed(args) = &last.arguments else {
        return None;
    };
    match args.args.iter().collect::<Vec<_>>().as_slice() {
        [GenericArgument::Type(t)] => Some(t),
        _ => None,
    }
}

fn is_plain(ty: &Type, name: &str) -> bool {
    matches!(ty, Type::Path(p) if p.qself.is_none() && p.path.is_ident(name))
}

fn attribute<'a>(attrs: &'a [Attribute], names: &[&str]) -> Option<&'a Attribute> {
    attrs
        .iter()
        .find(|a| names.iter().any(|n| a.path().is_ident(n)))
}

/// Reads a particle model's struct, reporting every problem to `errors`.
pub(crate) fn parse_struct<'a>(item: &'a ItemStruct, errors: &mut Errors) -> Option<Particles<'a>> {
    if !item.generics.params.is_empty() || item.generics.where_clause.is_some() {
        errors.at(
            &item.generics,
            "generic models are not supported; use concrete `f64` fields",
        );
    }
    let mut position = None;
    let mut velocity = None;
    let mut mass = None;
    let mut pinned = None;
    let mut dims = Vec::new();
    for field in &item.fields {
        let Some(ident) = field.ident.as_ref() else {
            errors.at(field, "a model must be a struct with named fields");
            return None;
        };
        if let Some(attr) = attribute(&field.attrs, &["state"]) {
            errors.at(
                attr,
                "`#[state]` cannot be mixed with particle fields; a particle model has \
                 `#[position]`/`#[velocity]` fields of type `Vec<Vector3<f64>>`",
            );
            continue;
        }
        let Some(attr) = attribute(&field.attrs, &FIELD_ATTRIBUTES) else {
            continue;
        };
        if let Err(e) = attr.meta.require_path_only() {
            errors.push(syn::Error::new(
                e.span(),
                "this attribute takes no arguments",
            ));
        }
        let name = attr
            .path()
            .get_ident()
            .map(Ident::to_string)
            .unwrap_or_default();
        let slot = match name.as_str() {
            "position" | "velocity" => {
                let dim = vec_element(&field.ty)
                    .and_then(shape_of)
                    .and_then(|s| match s {
                        Shape::Vector(d @ (2 | 3)) => Some(d),
                        _ => None,
                    });
                match dim {
                    Some(d) => dims.push((d, &field.ty)),
                    None => errors.at(
                        &field.ty,
                        format_args!(
                            "a particle model's `#[{name}]` field must be `Vec<Vector3<f64>>` or \
                             `Vec<Vector2<f64>>` (one vector per particle)"
                        ),
                    ),
                }
                if name == "position" {
                    &mut position
                } else {
                    &mut velocity
                }
            }
            "mass" => {
                if !vec_element(&field.ty).is_some_and(|t| is_plain(t, "f64")) {
                    errors.at(
                        &field.ty,
                        "`#[mass]` must be `Vec<f64>`, one mass per particle",
                    );
                }
                &mut mass
            }
            _ => {
                if !vec_element(&field.ty).is_some_and(|t| is_plain(t, "usize")) {
                    errors.at(
                        &field.ty,
                        "`#[pinned]` must be `Vec<usize>`, the indices of the pinned particles",
                    );
                }
                &mut pinned
            }
        };
        if slot.is_some() {
            errors.at(
                attr,
                format_args!("a particle model has one `#[{name}]` field; this is a second"),
            );
        }
        *slot = Some(ident);
    }
    if let [(d0, _), rest @ ..] = dims.as_slice()
        && let Some((_, ty)) = rest.iter().find(|(d, _)| d != d0)
    {
        errors.at(ty, "positions and velocities must have the same dimension");
    }
    let missing = |what: &str| {
        format!(
            "particle model `{}` needs a `#[{what}]` field; a particle model has `#[position]` \
             and `#[velocity]` fields (`Vec<Vector3<f64>>`), `#[mass]` (`Vec<f64>`) and \
             optionally `#[pinned]` (`Vec<usize>`)",
            item.ident
        )
    };
    for (what, found) in [
        ("position", position.is_some()),
        ("velocity", velocity.is_some()),
        ("mass", mass.is_some()),
    ] {
        if !found {
            errors.at_span(item.ident.span(), missing(what));
        }
    }
    Some(Particles {
        item,
        dim: dims.first()?.0,
        position: position?,
        velocity: velocity?,
        mass: mass?,
        pinned,
    })
}

/// The struct as the user wrote it, minus odyn's field attributes.
pub(crate) fn strip(item: &ItemStruct) -> ItemStruct {
    let mut item = item.clone();
    for field in &mut item.fields {
        field
            .attrs
            .retain(|a| !FIELD_ATTRIBUTES.iter().any(|n| a.path().is_ident(n)));
    }
    item
}

/// The state type of a particle model: an alias of the runtime's.
pub(crate) fn state(particles: &Particles<'_>) -> TokenStream {
    let vis = &particles.item.vis;
    let name = particles.state_ident();
    let d = proc_macro2::Literal::usize_unsuffixed(particles.dim);
    let doc = format!(
        "The state of [`{}`], generated by `#[system]`: every particle's position, then every \
         velocity.",
        particles.item.ident
    );
    quote! {
        #[doc = #doc]
        #vis type #name = ::odyn::particles::ParticleState<#d>;
    }
}

/// Which elements a kernel runs over.
enum Over {
    /// `#[pair(field)]`: the links in `self.field`.
    Pairs(Ident),
    /// `#[particle]`: every particle.
    Particles,
}

/// One force kernel.
struct Kernel {
    over: Over,
    f: ImplItemFn,
    /// `#[particle]` kernels: whether the first argument is the particle index.
    index: bool,
    /// The vector arguments: positions, then velocities when the kernel takes them.
    vectors: Vec<Ident>,
}

impl Kernel {
    fn reads_velocity(&self) -> bool {
        let positions = match self.over {
            Over::Pairs(_) => 2,
            Over::Particles => 1,
        };
        self.vectors.len() > positions
    }
}

/// The impl block's kernels and potential.
struct Functions {
    kernels: Vec<Kernel>,
    potential: Option<(ImplItemFn, syn::Block)>,
}

fn kernel_attribute(f: &ImplItemFn) -> Option<&Attribute> {
    attribute(&f.attrs, &["pair", "particle"])
}

fn parse_kernels(imp: &ItemImpl, particles: &Particles<'_>, errors: &mut Errors) -> Functions {
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
                let (_, reads) = crate::functions::rewrite(&f.block, &rewriter_model, name, errors);
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
            let (body, _) = crate::functions::rewrite(&f.block, &rewriter_model, name, errors);
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
        Some(FnArg::Receiver(r)) if r.reference.is_some() && r.mutability.is_none() => {}
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
        if let Err(e) = attr.meta.require_path_only() {
            errors.push(syn::Error::new(
                e.span(),
                "`#[particle]` takes no arguments",
            ));
        }
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
        Some(FnArg::Receiver(r)) if r.reference.is_some() && r.mutability.is_none() => {}
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
        let is_vector = matches!(shape_of(&t.ty), Some(Shape::Vector(d)) if d == particles.dim);
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
        if matches!(shape_of(ty), Some(Shape::Vector(d)) if d == particles.dim))
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

/// The impl block of a particle model: kernels → blocks → runtime trait impls.
pub(crate) fn expand_impl(args: &Args, item: &ItemStruct, imp: &ItemImpl) -> TokenStream {
    let mut errors = Errors::default();
    let Some(particles) = parse_struct(item, &mut errors) else {
        return crate::errors::with_error(
            strip_kernel_attributes(imp),
            errors.finish().expect_err("a rejected model has errors"),
        );
    };
    let functions = parse_kernels(imp, &particles, &mut errors);
    if let Some((ident, info)) = &args.integrator
        && info.needs_velocity_free_forces
        && let Some(kernel) = functions.kernels.iter().find(|k| k.reads_velocity())
    {
        errors.at(
            ident,
            format_args!(
                "`{ident}` needs forces that do not read velocities, but kernel `{}` takes \
                 velocities; use `VelocityVerlet` or `Leapfrog`",
                kernel.f.sig.ident
            ),
        );
    }
    if let (Some(no), Some((ident, info))) = (&args.no_jacobian, &args.integrator)
        && info.needs_jacobian
    {
        errors.at(
            no,
            format_args!("`{ident}` needs the Jacobian that `jacobian = false` turns off"),
        );
    }
    let mut lowered = Vec::new();
    if args.no_jacobian.is_none() {
        let model = particles.parameter_model();
        for kernel in &functions.kernels {
            match lower::lower_kernel(
                &model,
                &kernel.f,
                &kernel.vectors,
                particles.dim,
                particles.dim,
            ) {
                Ok(l) => lowered.push(l),
                Err(error) => errors.push(error),
            }
        }
    }
    if let Err(error) = errors.finish() {
        // The kernel attributes are odyn's: left in, rustc would add "cannot find attribute".
        let rejected = crate::errors::with_error(strip_kernel_attributes(imp), error);
        let stub = crate::generate::stub_model(&item.ident, &particles.state_ident());
        return quote!(#rejected #stub);
    }
    let jacobian = (args.no_jacobian.is_none()).then_some(lowered);
    generate(&particles, args, &functions, imp, jacobian)
}

fn generate(
    particles: &Particles<'_>,
    args: &Args,
    functions: &Functions,
    imp: &ItemImpl,
    jacobian: Option<Vec<Lowered>>,
) -> TokenStream {
    let self_ty = &imp.self_ty;
    let name = particles.item.ident.to_string();
    let state = particles.state_ident();
    let d = proc_macro2::Literal::usize_unsuffixed(particles.dim);
    let vector = particles.vector_type();
    let (x, v, mass) = (particles.position, particles.velocity, particles.mass);
    let (x_name, v_name, mass_name) = (x.to_string(), v.to_string(), mass.to_string());
    let pinned = match particles.pinned {
        Some(p) => quote!(&self.#p),
        None => quote!(&[]),
    };
    let defaults = crate::generate::attribute_defaults(args);
    let link_lists = functions.kernels.iter().filter_map(|k| match &k.over {
        Over::Pairs(field) => {
            let name = field.to_string();
            Some(quote!((#name, &self.#field as &dyn ::odyn::particles::LinkList)))
        }
        Over::Particles => None,
    });
    let forces = functions.kernels.iter().map(|k| {
        let name = &k.f.sig.ident;
        match &k.over {
            Over::Pairs(field) => {
                let call = if k.reads_velocity() {
                    quote!(self.#name(link, *xa, *xb, *va, *vb))
                } else {
                    quote!(self.#name(link, *xa, *xb))
                };
                quote! {
                    ::odyn::particles::pair_forces(&self.#field, x, v, force, |link, xa, xb, va, vb| #call);
                }
            }
            Over::Particles => {
                let index = k.index.then(|| quote!(i,));
                let velocity = k.reads_velocity().then(|| quote!(, *v));
                quote! {
                    ::odyn::particles::particle_forces(x, v, force, |i, x, v| self.#name(#index *x #velocity));
                }
            }
        }
    });
    let reads_velocity = functions.kernels.iter().any(Kernel::reads_velocity);
    let (potential_fn, potential) = match &functions.potential {
        Some((f, body)) => {
            let (lx, lv) = (
                crate::functions::state_local(x),
                crate::functions::state_local(v),
            );
            let receiver = match f.sig.inputs.first() {
                Some(FnArg::Receiver(r)) => r.to_token_stream(),
                _ => quote!(&self),
            };
            (
                quote! {
                    #[doc(hidden)]
                    #[inline]
                    #[allow(unused_variables, non_snake_case)]
                    fn __odyn_potential(#receiver, #lx: &[#vector], #lv: &[#vector]) -> f64 #body
                },
                quote! {
                    // The runtime calls the rewritten copy; this marks the original used.
                    let _ = Self::potential;
                    ::core::option::Option::Some(self.__odyn_potential(x, v))
                },
            )
        }
        None => (TokenStream::new(), quote!(::core::option::Option::None)),
    };
    let common = quote! {
        #[inline(always)]
        fn masses(&self) -> &[f64] {
            &self.#mass
        }
        #[inline(always)]
        fn pinned(&self) -> &[usize] {
            #pinned
        }
        fn per_particle(&self) -> [(&'static str, usize); 3] {
            [(#x_name, self.#x.len()), (#v_name, self.#v.len()), (#mass_name, self.#mass.len())]
        }
        fn link_lists(&self) -> ::std::vec::Vec<(&'static str, &dyn ::odyn::particles::LinkList)> {
            ::std::vec![#(#link_lists),*]
        }
        #[inline]
        fn add_forces(&self, _: f64, x: &[#vector], v: &[#vector], force: &mut [#vector]) {
            #(#forces)*
        }
        fn potential_of(&self, x: &[#vector], v: &[#vector]) -> ::core::option::Option<f64> {
            #potential
        }
    };
    let (jacobian_fns, jacobian_impl, jacobian_assoc) = match jacobian {
        Some(lowered) => {
            let (fns, calls): (Vec<_>, Vec<_>) = functions
                .kernels
                .iter()
                .zip(lowered)
                .map(|(k, l)| kernel_jacobian(particles, k, l))
                .unzip();
            (
                quote!(#(#fns)*),
                quote! {
                    #[automatically_derived]
                    impl ::odyn::particles::ParticleSystem<#d> for #self_ty {
                        #[inline]
                        fn add_force_jacobian(
                            &self,
                            _: f64,
                            x: &[#vector],
                            v: &[#vector],
                            jacobian: &mut ::odyn::particles::ParticleJacobian<#d>,
                        ) {
                            #(#calls)*
                        }
                        #common
                    }
                    #[automatically_derived]
                    impl ::odyn::Jacobian for #self_ty {
                        type Matrix = ::odyn::particles::ParticleJacobian<#d>;
                        /// Empty: a particle model's pattern comes from its topology at run time.
                        const NONZEROS: &'static [(usize, usize)] = &[];
                        fn jacobian_matrix(&self, state: &#state) -> Self::Matrix {
                            ::odyn::particles::jacobian_matrix(self, state)
                        }
                        #[inline]
                        fn jacobian(&self, t: f64, y: &#state, jacobian: &mut Self::Matrix) {
                            ::odyn::particles::jacobian(self, t, y, jacobian)
                        }
                        /// Kernels do not read the time: ∂f/∂t = 0.
                        const TIME_DEPENDENT: bool = false;
                        #[inline]
                        fn time_derivative(&self, _: f64, _: &#state, dfdt: &mut #state) {
                            ::odyn::State::as_mut_slice(dfdt).fill(0.0);
                        }
                    }
                },
                quote! {
                    type Jacobian = Self;
                    #[inline(always)]
                    fn as_jacobian(&self) -> ::core::option::Option<&Self> {
                        ::core::option::Option::Some(self)
                    }
                },
            )
        }
        None => (
            TokenStream::new(),
            quote! {
                #[automatically_derived]
                impl ::odyn::particles::ParticleSystem<#d> for #self_ty {
                    fn add_force_jacobian(
                        &self,
                        _: f64,
                        _: &[#vector],
                        _: &[#vector],
                        _: &mut ::odyn::particles::ParticleJacobian<#d>,
                    ) {
                    }
                    #common
                }
            },
            quote! {
                type Jacobian = ::odyn::Unavailable<Self>;
                #[inline(always)]
                fn as_jacobian(&self) -> ::core::option::Option<&Self::Jacobian> {
                    ::core::option::Option::None
                }
            },
        ),
    };
    let imp = strip_kernel_attributes(imp);
    quote! {
        #imp
        #[automatically_derived]
        impl #self_ty {
            #potential_fn
            #jacobian_fns
        }
        #jacobian_impl
        #[automatically_derived]
        impl ::odyn::Model for #self_ty {
            type State = #state;
            type SecondOrder = Self;
            const NAME: &'static str = #name;
            #defaults
            fn state(&self) -> #state {
                ::odyn::particles::ParticleState::from_fields(&self.#x, &self.#v, [#x_name, #v_name])
            }
            #[inline]
            fn derivative(&self, t: f64, y: &#state, dydt: &mut #state) {
                ::odyn::particles::derivative(self, t, y, dydt)
            }
            fn energy(&self, state: &#state) -> ::core::option::Option<f64> {
                ::odyn::particles::energy(self, state)
            }
            #[inline(always)]
            fn as_second_order(&self) -> ::core::option::Option<&Self> {
                ::core::option::Option::Some(self)
            }
            #jacobian_assoc
            fn check(&self, state: &#state) -> ::odyn::Result<()> {
                ::odyn::particles::check(self, state)
            }
        }
        #[automatically_derived]
        impl ::odyn::SecondOrder for #self_ty {
            const READS_VELOCITY: bool = #reads_velocity;
            #[inline]
            fn acceleration(&self, t: f64, y: &#state, accel: &mut #state) {
                ::odyn::particles::acceleration(self, t, y, accel)
            }
        }
    }
}

/// A kernel's derivative blocks as a hidden method, and the call that hands them to the runtime.
fn kernel_jacobian(
    particles: &Particles<'_>,
    kernel: &Kernel,
    lowered: Lowered,
) -> (TokenStream, TokenStream) {
    let dim = particles.dim;
    let d = proc_macro2::Literal::usize_unsuffixed(dim);
    let Lowered {
        mut graph,
        outputs,
        prologue,
        ..
    } = lowered;
    let mut differentiator = crate::derivative::Differentiator::default();
    // blocks[k][(r, c)] = ∂fᵣ/∂(vector k)_c
    let blocks: Vec<Vec<ExprId>> = (0..kernel.vectors.len())
        .map(|k| {
            let mut entries = Vec::with_capacity(dim * dim);
            for c in 0..dim {
                for &f in &outputs {
                    entries.push(differentiator.derivative(&mut graph, f, dim * k + c));
                }
            }
            entries
        })
        .collect();
    let components: Vec<TokenStream> = kernel
        .vectors
        .iter()
        .flat_map(|name| (0..dim).map(move |i| quote!(#name[#i])))
        .collect();
    let roots: Vec<ExprId> = blocks.iter().flatten().copied().collect();
    let lets = straight_line(&graph, &roots, &components);
    let prologue = prologue_tokens(&prologue);
    let matrices = blocks.iter().map(|entries| {
        let columns = entries.chunks(dim).map(|column| {
            let rows = column.iter().map(|&id| operand(&graph, id, &components));
            quote!([#(#rows),*])
        });
        quote! {
            ::odyn::__private::nalgebra::SMatrix::<f64, #d, #d>::from_array_storage(
                ::odyn::__private::nalgebra::ArrayStorage([#(#columns),*]),
            )
        }
    });
    let count = proc_macro2::Literal::usize_unsuffixed(kernel.vectors.len());
    let name = &kernel.f.sig.ident;
    let hidden = format_ident!("__odyn_{}_jacobian", name, span = Span::mixed_site());
    let inputs = &kernel.f.sig.inputs;
    let function = quote! {
        #[doc(hidden)]
        #[inline(always)]
        #[allow(unused_variables, unused_parens, non_snake_case, clippy::all)]
        fn #hidden(#inputs) -> [::odyn::__private::nalgebra::SMatrix<f64, #d, #d>; #count] {
            #(#prologue)*
            #(#lets)*
            [#(#matrices),*]
        }
    };
    let zero = quote!(::odyn::__private::nalgebra::SMatrix::<f64, #d, #d>::zeros());
    let call = match &kernel.over {
        Over::Pairs(field) => {
            let body = if kernel.reads_velocity() {
                quote!(self.#hidden(link, *xa, *xb, *va, *vb))
            } else {
                quote! {{
                    let [dxa, dxb] = self.#hidden(link, *xa, *xb);
                    [dxa, dxb, #zero, #zero]
                }}
            };
            quote!(jacobian.pair_blocks(&self.#field, x, v, |link, xa, xb, va, vb| #body);)
        }
        Over::Particles => {
            let index = kernel.index.then(|| quote!(i,));
            let body = if kernel.reads_velocity() {
                quote!(self.#hidden(#index *x, *v))
            } else {
                quote! {{
                    let [dx] = self.#hidden(#index *x);
                    [dx, #zero]
                }}
            };
            quote!(jacobian.particle_blocks(x, v, |i, x, v| #body);)
        }
    };
    (function, call)
}

/// The impl block with `#[pair]`/`#[particle]` removed from its kernels (they are odyn's).
fn strip_kernel_attributes(imp: &ItemImpl) -> ItemImpl {
    let mut imp = imp.clone();
    for member in &mut imp.items {
        if let ImplItem::Fn(f) = member {
            f.attrs
                .retain(|a| !(a.path().is_ident("pair") || a.path().is_ident("particle")));
        }
    }
    imp
}
