//! Stage 3: what the attribute's integrator asks of the model, checked once for every kind.
//!
//! A front-end says what its model is (first- or second-order, whether its forces read
//! velocities); the checks and their messages live here. Those that need only the struct run
//! in the struct's expansion ([`structure`]), so a model the integrator cannot step is rejected
//! before its impl block is read; the one that needs the force functions runs in the impl
//! block's ([`forces`]).

use proc_macro2::TokenStream;

use crate::args::{Args, adaptive_names};
use crate::errors::Errors;

/// How a first-order model says what it is, for the message that refuses it a second-order
/// integrator.
pub(crate) struct FirstOrder {
    /// What a second-order model of this kind has: "`#[position]`/`#[velocity]` fields".
    pub(crate) second_order: &'static str,
    /// The model and why it is first-order: "`Lorenz` is first-order (`#[state]` fields)".
    pub(crate) model: String,
    /// The integrators to suggest instead.
    pub(crate) instead: &'static str,
}

/// A force that reads velocities, for the message that refuses it an integrator needing
/// velocity-free forces.
pub(crate) struct VelocityRead {
    /// Which force reads which velocity: "`acceleration` reads `self.v`".
    pub(crate) reader: String,
    /// Where, with its own message, when one read can be pointed at.
    pub(crate) at: Option<(TokenStream, String)>,
}

/// The checks of the struct's expansion: tolerances against a fixed-step integrator,
/// `jacobian = false` against one that needs the Jacobian, and a first-order model (`Some`
/// here) against one that needs a second-order model.
pub(crate) fn structure(args: &Args, first_order: Option<&FirstOrder>, errors: &mut Errors) {
    let Some((ident, info)) = &args.integrator else {
        return;
    };
    if let Some(tolerance) = args.rtol.as_ref().or(args.atol.as_ref())
        && !info.adaptive
    {
        errors.at(
            tolerance,
            format_args!(
                "`{ident}` steps with a fixed `dt` and has no error estimate to hold to a \
                 tolerance; `rtol`/`atol` need an adaptive integrator ({})",
                adaptive_names()
            ),
        );
    }
    if let Some(no) = args.jacobian.off()
        && info.needs_jacobian
    {
        errors.at(
            no,
            format_args!("`{ident}` needs the Jacobian that `jacobian = false` turns off"),
        );
    }
    if let Some(FirstOrder {
        second_order,
        model,
        instead,
    }) = first_order
        && info.needs_second_order
    {
        errors.at(
            ident,
            format_args!(
                "`{ident}` needs a second-order model ({second_order}), but {model}; use \
                 {instead}"
            ),
        );
    }
}

/// The check of the impl block's expansion: forces that read velocities (`read`, the first such)
/// against an integrator that needs them free of velocities.
pub(crate) fn forces(args: &Args, read: Option<VelocityRead>, errors: &mut Errors) {
    let (Some((ident, info)), Some(read)) = (&args.integrator, read) else {
        return;
    };
    if !info.needs_velocity_free_forces {
        return;
    }
    errors.at(
        ident,
        format_args!(
            "`{ident}` needs forces that do not read velocities, but {}; use `VelocityVerlet` or \
             `Leapfrog`",
            read.reader
        ),
    );
    if let Some((tokens, message)) = read.at {
        errors.at(tokens, message);
    }
}
