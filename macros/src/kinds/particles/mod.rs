//! The particle model front-end: `Vec<VectorD<f64>>` positions and velocities, forces as
//! per-element kernels.
//!
//! The struct gives the particle fields ([`parse_struct`]); the impl block gives the kernels
//! ([`kernels::parse_kernels`]); each kernel body is lowered by the shared
//! [`crate::lower::lower_kernel`] with its vector arguments as the variables and differentiated
//! into D×D blocks; [`generate`] emits the blocks as straight-line code and the runtime trait
//! impls, which leave the loops over particles and links to `odyn::particles`.

mod generate;
mod kernels;

use proc_macro2::TokenStream;
use quote::quote;
use syn::{Ident, ItemImpl, ItemStruct};

use crate::args::Args;
use crate::errors::Errors;
use crate::kinds::{FrontEnd, Impl, Struct};
use crate::lower;
use crate::model::{Len, Model, Order, Role, Shape, StateField, shape_of, state_ident};
use crate::syntax::{attribute, has_attribute, is_plain, no_arguments, vec_element};
use crate::validate::{self, VelocityRead};

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
        state_ident(&self.item.ident)
    }

    /// The model as the body rewriter sees it: positions and velocities are state.
    fn rewriter_model(&self) -> Model<'_> {
        let field = |ident, role| StateField {
            ident,
            role,
            shape: Shape::Vector(Len::Known(self.dim)),
        };
        Model {
            item: self.item,
            order: Order::Second,
            states: vec![
                field(self.position, Role::Position),
                field(self.velocity, Role::Velocity),
            ],
            params: Vec::new(),
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
        has_attribute(&f.attrs, "mass")
            || has_attribute(&f.attrs, "pinned")
            || (attribute(&f.attrs, &["position", "velocity"]).is_some()
                && vec_element(&f.ty).is_some())
    })
}

/// Reads a particle model's struct, reporting every problem to `errors`.
pub(crate) fn parse_struct<'a>(item: &'a ItemStruct, errors: &mut Errors) -> Option<Particles<'a>> {
    let mut position = None;
    let mut velocity = None;
    let mut mass = None;
    let mut pinned = None;
    let mut dims = Vec::new();
    for field in &item.fields {
        // Refused before the front-end with its own error (`kinds::expand_struct`).
        let ident = field.ident.as_ref()?;
        if let Some(attr) = attribute(&field.attrs, &["state"]) {
            errors.at(
                attr,
                "`#[state]` cannot be mixed with particle fields; a particle model has \
                 `#[position]`/`#[velocity]` fields of type `Vec<Vector3<f64>>`",
            );
            continue;
        }
        if let Some(attr) = attribute(&field.attrs, &["algebraic", "field"]) {
            let name = attr.path().get_ident().map(Ident::to_string);
            errors.at(
                attr,
                format_args!(
                    "`#[{}]` is not a particle model's attribute: a particle model has \
                     `#[position]`, `#[velocity]`, `#[mass]` and `#[pinned]` fields and its \
                     forces in `#[pair]`/`#[particle]` kernels (algebraic components are for \
                     fixed-size and field models, grids for field models)",
                    name.unwrap_or_default()
                ),
            );
            continue;
        }
        let Some(attr) = attribute(&field.attrs, &FIELD_ATTRIBUTES) else {
            continue;
        };
        no_arguments(attr, "this attribute takes no arguments", errors);
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
                        Shape::Vector(Len::Known(d @ (2 | 3))) => Some(d),
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

/// The particle front-end: structs with `Vec` positions and velocities, `#[mass]`, `#[pinned]`.
pub(crate) struct Kind;

impl FrontEnd for Kind {
    fn recognises(&self, item: &ItemStruct) -> bool {
        is_particle_model(item)
    }

    fn method_attributes(&self) -> &'static [&'static str] {
        &["pair", "particle"]
    }

    /// The struct half: the state type when accepted (a particle model is second-order).
    fn expand_struct(&self, _: &Args, item: &ItemStruct, errors: &mut Errors) -> Option<Struct> {
        let particles = parse_struct(item, errors)?;
        Some(Struct {
            state: state(&particles),
            first_order: None,
        })
    }

    /// The impl block of a particle model: kernels → blocks → runtime trait impls.
    fn expand_impl(
        &self,
        args: &Args,
        item: &ItemStruct,
        imp: &ItemImpl,
        errors: &mut Errors,
    ) -> Impl {
        let Some(particles) = parse_struct(item, errors) else {
            return Impl::Rejected {
                silenced: None,
                stand_ins: TokenStream::new(),
            };
        };
        let before = errors.len();
        let helpers = crate::helpers::parse(imp, &particles.rewriter_model(), errors);
        let helpers_ok = errors.len() == before;
        let functions = kernels::parse_kernels(imp, &particles, &helpers, errors);
        let velocity_read = functions.kernels.iter().find(|k| k.reads_velocity());
        let velocity_read = velocity_read.map(|kernel| VelocityRead {
            reader: format!("kernel `{}` takes velocities", kernel.f.sig.ident),
            at: None,
        });
        validate::forces(args, velocity_read, errors);
        let mut lowered = Vec::new();
        if args.jacobian.off().is_none() && helpers_ok {
            let model = Model::parameters(particles.item, Order::Second);
            for kernel in &functions.kernels {
                match lower::lower_kernel(
                    &model,
                    &helpers,
                    &kernel.f,
                    &kernel.vectors,
                    particles.dim,
                    particles.dim,
                    None,
                ) {
                    Ok(l) => lowered.push(l),
                    Err(error) => errors.push(error),
                }
            }
        }
        if !errors.is_empty() {
            return Impl::Rejected {
                silenced: None,
                stand_ins: TokenStream::new(),
            };
        }
        let jacobian = (args.jacobian.off().is_none()).then_some(lowered);
        Impl::Accepted(generate::generate(
            &particles, args, &functions, imp, jacobian,
        ))
    }
}
