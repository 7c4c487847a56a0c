//! A model stepped by a method the reader picks: [`Run`] hides which integrator type each
//! method's [`Stepper`] is.

use odyn::{Integrator, Model, Stepper};

/// One stepper, whatever its integrator.
pub trait Run<S> {
    /// One step of dt.
    fn step(&mut self) -> odyn::Result<()>;
    /// The state.
    fn state(&self) -> &S;
    /// The time.
    fn t(&self) -> f64;
}

impl<M: Model, I: Integrator<M>> Run<M::State> for Stepper<'static, M, I> {
    fn step(&mut self) -> odyn::Result<()> {
        Stepper::step(self)
    }

    fn state(&self) -> &M::State {
        Stepper::state(self)
    }

    fn t(&self) -> f64 {
        Stepper::t(self)
    }
}

/// A boxed [`Stepper`] of `$method` on `$model` (a `&'static` model) from `$state` at t = 0 with
/// step `$dt`, for the methods listed; any other method is an [`odyn::Error::InvalidInput`].
macro_rules! stepper {
    ($method:expr, $model:expr, $state:expr, $dt:expr; $($variant:ident)|+) => {
        match $method {
            $(odyn::Method::$variant => {
                let stepper = odyn::Stepper::<_, odyn::integrators::$variant<_>>::new(
                    $model, $state, 0.0, $dt,
                )?;
                Ok(Box::new(stepper) as Box<dyn $crate::run::Run<_>>)
            })+
            other => Err(odyn::Error::InvalidInput {
                field: "method".into(),
                reason: format!("{} is not offered in this panel", other.info().label),
            }),
        }
    };
}

pub(crate) use stepper;
