//! [`Unavailable`]: the capability type of a model that lacks a capability.

use std::convert::Infallible;
use std::marker::PhantomData;

use super::{Jacobian, Model, SecondOrder};
use crate::Method;

/// The capability type of a model that lacks it (see [`Model`]): it has no values, so a method
/// that needs the capability can be named for such a model but never run on it.
#[derive(Debug)]
pub enum Unavailable<M> {
    #[doc(hidden)]
    Never(Infallible, PhantomData<M>),
}

impl<M: Model> super::Sealed for Unavailable<M> {}

impl<M: Model> Model for Unavailable<M> {
    type State = M::State;
    type SecondOrder = Self;
    type Jacobian = Self;
    const NAME: &'static str = M::NAME;
    const DEFAULT_METHOD: Method = M::DEFAULT_METHOD;
    const DEFAULT_DT: Option<f64> = M::DEFAULT_DT;
    const DEFAULT_RTOL: Option<f64> = M::DEFAULT_RTOL;
    const DEFAULT_ATOL: Option<f64> = M::DEFAULT_ATOL;
    const AVAILABLE: bool = false;

    fn state(&self) -> Self::State {
        self.never()
    }
    fn derivative(&self, _: f64, _: &Self::State, _: &mut Self::State) {
        self.never()
    }
    fn energy(&self, _: &Self::State) -> Option<f64> {
        self.never()
    }
    fn as_second_order(&self) -> Option<&Self> {
        self.never()
    }
    fn as_jacobian(&self) -> Option<&Self> {
        self.never()
    }
}

impl<M: Model> SecondOrder for Unavailable<M> {
    const READS_VELOCITY: bool = false;
    fn acceleration(&self, _: f64, _: &Self::State, _: &mut Self::State) {
        self.never()
    }
}

impl<M: Model> Jacobian for Unavailable<M> {
    type Matrix = nalgebra::SMatrix<f64, 0, 0>;
    const NONZEROS: &'static [(usize, usize)] = &[];
    const TIME_DEPENDENT: bool = false;
    fn time_derivative(&self, _: f64, _: &Self::State, _: &mut Self::State) {
        self.never()
    }
    fn jacobian_matrix(&self, _: &Self::State) -> Self::Matrix {
        self.never()
    }
    fn jacobian(&self, _: f64, _: &Self::State, _: &mut Self::Matrix) {
        self.never()
    }
}

impl<M> Unavailable<M> {
    fn never(&self) -> ! {
        match *self {
            Unavailable::Never(never, _) => match never {},
        }
    }
}
