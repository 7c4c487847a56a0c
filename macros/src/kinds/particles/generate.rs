//! Code generation for particle models: each kernel's derivative blocks as straight-line code,
//! and the `ParticleSystem`, `Model`, `SecondOrder` and `Jacobian` impls, which call into
//! `odyn::particles`.

use proc_macro2::{Span, TokenStream};
use quote::{ToTokens, format_ident, quote};
use syn::{FnArg, ItemImpl};

use super::Particles;
use super::kernels::{Functions, Kernel, Over};
use crate::args::Args;
use crate::generate::{
    ModelImpl, evaluation, hidden_fn, operand, runtime_jacobian, time_independent,
};
use crate::ir::ExprId;
use crate::lower::Lowered;

pub(super) fn generate(
    particles: &Particles<'_>,
    args: &Args,
    functions: &Functions,
    imp: &ItemImpl,
    jacobian: Option<Vec<Lowered>>,
) -> TokenStream {
    let self_ty = &imp.self_ty;
    let state = particles.state_ident();
    let d = proc_macro2::Literal::usize_unsuffixed(particles.dim);
    let vector = particles.vector_type();
    let (x, v, mass) = (particles.position, particles.velocity, particles.mass);
    let (x_name, v_name, mass_name) = (x.to_string(), v.to_string(), mass.to_string());
    let pinned = match particles.pinned {
        Some(p) => quote!(&self.#p),
        None => quote!(&[]),
    };
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
                    ::odyn::__private::particles::pair_forces(&self.#field, x, v, force, |link, xa, xb, va, vb| #call);
                }
            }
            Over::Particles => {
                let index = k.index.then(|| quote!(i,));
                let velocity = k.reads_velocity().then(|| quote!(, *v));
                quote! {
                    ::odyn::__private::particles::particle_forces(x, v, force, |i, x, v| self.#name(#index *x #velocity));
                }
            }
        }
    });
    let reads_velocity = functions.kernels.iter().any(Kernel::reads_velocity);
    let (potential_fn, potential) = match &functions.potential {
        Some((f, body)) => {
            let (lx, lv) = (
                crate::rewrite::state_local(x),
                crate::rewrite::state_local(v),
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
    let has_jacobian = jacobian.is_some();
    let (jacobian_fns, jacobian_impl) = match jacobian {
        Some(lowered) => {
            let (fns, calls): (Vec<_>, Vec<_>) = functions
                .kernels
                .iter()
                .zip(lowered)
                .map(|(k, l)| kernel_jacobian(particles, k, l))
                .unzip();
            let jacobian_impl = runtime_jacobian(
                self_ty,
                &state,
                "particles",
                quote!(::odyn::particles::ParticleJacobian<#d>),
                "a particle model's pattern comes from its topology at run time",
                time_independent(&state, "Kernels do not read the time"),
            );
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
                    #jacobian_impl
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
        ),
    };
    let model_impl = ModelImpl {
        methods: quote! {
            fn state(&self) -> #state {
                ::odyn::__private::particles::state(&self.#x, &self.#v, [#x_name, #v_name])
            }
            #[inline]
            fn derivative(&self, t: f64, y: &#state, dydt: &mut #state) {
                ::odyn::__private::particles::derivative(self, t, y, dydt)
            }
            fn energy(&self, state: &#state) -> ::core::option::Option<f64> {
                ::odyn::__private::particles::energy(self, state)
            }
        },
        second_order: true,
        jacobian: has_jacobian,
        check: Some(quote!(::odyn::__private::particles::check(self, state))),
        ..ModelImpl::for_impl(imp, &particles.item.ident, quote!(#state), args)
    }
    .build();
    quote! {
        #[automatically_derived]
        impl #self_ty {
            #potential_fn
            #jacobian_fns
        }
        #jacobian_impl
        #model_impl
        #[automatically_derived]
        impl ::odyn::SecondOrder for #self_ty {
            const READS_VELOCITY: bool = #reads_velocity;
            #[inline]
            fn acceleration(&self, t: f64, y: &#state, accel: &mut #state) {
                ::odyn::__private::particles::acceleration(self, t, y, accel)
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
    let (prologue, lets) = evaluation(&graph, &roots, &components, &prologue);
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
    let function = hidden_fn(
        quote!(#hidden(#inputs) -> [::odyn::__private::nalgebra::SMatrix<f64, #d, #d>; #count]),
        quote!(#[inline(always)]),
        &TokenStream::new(),
        &prologue,
        quote!(#(#lets)* [#(#matrices),*]),
    );
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
            quote!(::odyn::__private::particles::pair_blocks(jacobian, &self.#field, x, v, |link, xa, xb, va, vb| #body);)
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
            quote!(::odyn::__private::particles::particle_blocks(jacobian, x, v, |i, x, v| #body);)
        }
    };
    (function, call)
}
