//! The traits `#[system]` implements for a model and the integrators are generic over.
//!
//! A [`Model`] is first-order, y′ = f(t, y). A model with `#[position]`/`#[velocity]` fields is
//! also [`SecondOrder`], q̈ = a(t, q, q̇): its state lays out every position, then every velocity,
//! so the split methods see the two halves of [`State::as_slice`].

use std::convert::Infallible;
use std::fmt::Debug;
use std::marker::PhantomData;

use crate::linalg::NewtonMatrix;
use crate::{Method, Result, Simulation};

/// A model's state: a list of `f64` components with names.
pub trait State: Clone + PartialEq + Debug {
    /// The components, positions before velocities for second-order models.
    fn as_slice(&self) -> &[f64];
    /// The components, mutably, in the order of [`State::as_slice`].
    fn as_mut_slice(&mut self) -> &mut [f64];
    /// The name of component `index` as CSV headers and errors show it (`x`, `r[1]`).
    fn component_name(&self, index: usize) -> String;

    /// A copy, allocated fallibly: how a run makes its copies of the state (the method's stages,
    /// the driver's buffers, the first sample), so that a state too large for the machine's
    /// memory ends the run with an error rather than aborting the process. Steps copy into
    /// these buffers with `clone_from` and allocate nothing.
    ///
    /// The default clones: a fixed-size state has no heap memory. [`crate::grid::GridState`]
    /// and [`crate::particles::ParticleState`] reserve their values with `try_reserve_exact`.
    ///
    /// Errors: [`crate::Error::InvalidInput`] naming the state's size when the copy cannot be
    /// allocated.
    fn try_clone(&self) -> Result<Self> {
        Ok(self.clone())
    }
}

/// A system of ordinary differential equations, y′ = f(t, y), with optional energy.
///
/// Implemented by `#[system]`; the runtime never asks a user to write it by hand. What a model
/// can do beyond f(t, y) shows as two capabilities, each an associated type that is `Self` when
/// the model has it and [`Unavailable`] when it does not: [`SecondOrder`] (a position/velocity
/// split, needed by the symplectic methods) and [`Jacobian`] (∂f/∂y, needed by implicit Euler).
pub trait Model {
    /// The typed state (`<Model>State`).
    type State: State;
    /// This model as a [`SecondOrder`] one.
    type SecondOrder: SecondOrder<State = Self::State>;
    /// This model as one with a [`Jacobian`].
    type Jacobian: Jacobian<State = Self::State>;
    /// The model's type name, for errors.
    const NAME: &'static str;
    /// The method named by `#[system(integrator = ...)]`, else [`Method::Rk4`].
    const DEFAULT_METHOD: Method;
    /// The step named by `#[system(dt = ...)]`.
    const DEFAULT_DT: Option<f64>;
    /// The relative tolerance named by `#[system(rtol = ...)]`.
    const DEFAULT_RTOL: Option<f64> = None;
    /// The absolute tolerance named by `#[system(atol = ...)]`.
    const DEFAULT_ATOL: Option<f64> = None;

    /// The state held in the model's own fields: the usual initial state.
    fn state(&self) -> Self::State;

    /// Writes f(t, y) into `dydt`.
    fn derivative(&self, t: f64, y: &Self::State, dydt: &mut Self::State);

    /// The model's energy at `state`, if it defines `fn energy`.
    fn energy(&self, state: &Self::State) -> Option<f64>;

    /// The model as a [`SecondOrder`] one, if it is.
    fn as_second_order(&self) -> Option<&Self::SecondOrder>;

    /// The model as one with a [`Jacobian`], if it has one.
    fn as_jacobian(&self) -> Option<&Self::Jacobian>;

    /// Checks that the model and `state` can be integrated at all, before any step: particle
    /// models check their topology and masses here. Fixed-size models have nothing to check.
    ///
    /// Errors: [`crate::Error::BadModel`] naming what is wrong.
    fn check(&self, state: &Self::State) -> Result<()> {
        let _ = state;
        Ok(())
    }

    /// Starts configuring a run from the model's own state, method and dt.
    fn simulate(&self) -> Simulation<'_, Self>
    where
        Self: Sized,
    {
        Simulation::new(self)
    }
}

/// A model with a position/velocity split, q̈ = a(t, q, q̇).
pub trait SecondOrder: Model {
    /// Whether `fn acceleration` reads a velocity field (determined by the macro from the body).
    const READS_VELOCITY: bool;

    /// Writes a(t, q, q̇) into the velocity components of `accel`; its position components are
    /// left as they were.
    fn acceleration(&self, t: f64, state: &Self::State, accel: &mut Self::State);
}

/// A model whose Jacobian ∂f/∂y the macro derived exactly from the body of its force function.
pub trait Jacobian: Model {
    /// The Jacobian's type: `SMatrix<f64, N, N>` for a state of N ≤ 32 components,
    /// [`crate::FaerDense`] above that, [`crate::particles::ParticleJacobian`] (sparse, sized at
    /// run time) for particle models.
    type Matrix: NewtonMatrix;
    /// The structural non-zeros (row, column), known at compile time; every other entry of the
    /// Jacobian is zero at every state. Empty for particle models, whose pattern comes from
    /// their topology at run time.
    const NONZEROS: &'static [(usize, usize)];

    /// A Jacobian for states like `state`, every buffer allocated: called once per run.
    fn jacobian_matrix(&self, state: &Self::State) -> Self::Matrix;

    /// Writes ∂f/∂y at (t, y) into `jacobian`, every entry.
    fn jacobian(&self, t: f64, y: &Self::State, jacobian: &mut Self::Matrix);

    /// Whether f reads the time, so ∂f/∂t may be non-zero (false for autonomous models: then
    /// methods that need ∂f/∂t skip it at no cost).
    const TIME_DEPENDENT: bool = true;

    /// Writes ∂f/∂t at (t, y) into `dfdt`.
    ///
    /// `#[system]` generates it exactly from the model's code, or as zero for an autonomous model.
    /// When the time reaches f through code it cannot differentiate (a call of the user's own
    /// function of `t`), this default is used: a central difference
    /// (f(t + h) − f(t − h))/(2h) with h = ε^⅓·max(1, |t|), accurate to about 1e-10 relative,
    /// which allocates one state per call.
    fn time_derivative(&self, t: f64, y: &Self::State, dfdt: &mut Self::State) {
        let h = f64::EPSILON.cbrt() * t.abs().max(1.0);
        let mut minus = y.clone();
        self.derivative(t + h, y, dfdt);
        self.derivative(t - h, y, &mut minus);
        for (d, m) in dfdt.as_mut_slice().iter_mut().zip(minus.as_slice()) {
            *d = (*d - m) / (2.0 * h);
        }
    }
}

/// The capability type of a model that lacks it (see [`Model`]): it has no values, so a method
/// that needs the capability can be named for such a model but never run on it.
#[derive(Debug)]
pub enum Unavailable<M> {
    #[doc(hidden)]
    Never(Infallible, PhantomData<M>),
}

impl<M: Model> Model for Unavailable<M> {
    type State = M::State;
    type SecondOrder = Self;
    type Jacobian = Self;
    const NAME: &'static str = M::NAME;
    const DEFAULT_METHOD: Method = M::DEFAULT_METHOD;
    const DEFAULT_DT: Option<f64> = M::DEFAULT_DT;
    const DEFAULT_RTOL: Option<f64> = M::DEFAULT_RTOL;
    const DEFAULT_ATOL: Option<f64> = M::DEFAULT_ATOL;

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

/// Positions and velocities of a second-order state: the two halves of its components.
#[inline(always)]
pub(crate) fn split(s: &[f64]) -> (&[f64], &[f64]) {
    s.split_at(s.len() / 2)
}

/// Mutable [`split`].
#[inline(always)]
pub(crate) fn split_mut(s: &mut [f64]) -> (&mut [f64], &mut [f64]) {
    let half = s.len() / 2;
    s.split_at_mut(half)
}

/// Safe views of fixed-size generated states as `f64` slices and `nalgebra` vectors.
pub mod flat {
    use nalgebra::SVector;

    /// A `#[repr(C)]` struct made only of `f64`, `[f64; N]` and `SVector<f64, N>` fields.
    ///
    /// # Safety
    /// The implementor must be `#[repr(C)]`, contain only those field types, and have
    /// `LEN * size_of::<f64>()` bytes; it is then layout-identical to `[f64; LEN]`. The size is
    /// checked again at compile time by every function here.
    pub unsafe trait FlatState: Copy {
        /// Number of `f64` components.
        const LEN: usize;
    }

    const fn check<T: FlatState, const N: usize>() {
        assert!(size_of::<T>() == N * size_of::<f64>());
        assert!(align_of::<T>() == align_of::<f64>());
    }

    /// The components of `state` as a slice.
    #[inline(always)]
    pub fn as_slice<T: FlatState>(state: &T) -> &[f64] {
        const { assert!(size_of::<T>() == T::LEN * size_of::<f64>()) };
        // SAFETY: `FlatState` guarantees `T` is layout-identical to `[f64; T::LEN]`.
        unsafe { core::slice::from_raw_parts((state as *const T).cast::<f64>(), T::LEN) }
    }

    /// The components of `state` as a mutable slice.
    #[inline(always)]
    pub fn as_mut_slice<T: FlatState>(state: &mut T) -> &mut [f64] {
        const { assert!(size_of::<T>() == T::LEN * size_of::<f64>()) };
        // SAFETY: as in `as_slice`; the borrow is unique.
        unsafe { core::slice::from_raw_parts_mut((state as *mut T).cast::<f64>(), T::LEN) }
    }

    /// `state` viewed as an `SVector<f64, N>` without copying; `N` must equal `T::LEN`.
    #[inline(always)]
    pub fn as_vector<T: FlatState, const N: usize>(state: &T) -> &SVector<f64, N> {
        const { check::<T, N>() };
        // SAFETY: `SVector<f64, N>` is `#[repr(C)]` over a `#[repr(transparent)]` `[[f64; N]; 1]`
        // and `T` is layout-identical to `[f64; N]` (checked above).
        unsafe { &*(state as *const T).cast::<SVector<f64, N>>() }
    }

    /// `state` viewed as a mutable `SVector<f64, N>` without copying.
    #[inline(always)]
    pub fn as_vector_mut<T: FlatState, const N: usize>(state: &mut T) -> &mut SVector<f64, N> {
        const { check::<T, N>() };
        // SAFETY: as in `as_vector`; the borrow is unique.
        unsafe { &mut *(state as *mut T).cast::<SVector<f64, N>>() }
    }

    /// Builds a state from a vector of its components.
    #[inline(always)]
    pub fn from_vector<T: FlatState, const N: usize>(vector: &SVector<f64, N>) -> T {
        const { check::<T, N>() };
        // SAFETY: every bit pattern of `[f64; N]` is a valid `T` (only `f64` fields), and the
        // layouts match (checked above).
        unsafe { core::mem::transmute_copy(vector) }
    }
}

/// Implements [`State`], [`flat::FlatState`], conversions and arithmetic for a state struct
/// generated by `#[system]`: `flat_state!(Name, LEN, ["x", "v"])`. Not a public API.
#[doc(hidden)]
#[macro_export]
macro_rules! __flat_state {
    ($state:ident, $len:literal, [$($name:literal),*]) => {
        // SAFETY: `#[system]` generates `$state` as `#[repr(C)]` with only `f64`, `[f64; N]` and
        // `SVector<f64, N>` fields totalling `$len` components; the size is asserted below.
        unsafe impl $crate::__private::FlatState for $state {
            const LEN: usize = $len;
        }

        const _: () = ::core::assert!(
            ::core::mem::size_of::<$state>() == $len * ::core::mem::size_of::<f64>()
        );

        impl $crate::State for $state {
            #[inline(always)]
            fn as_slice(&self) -> &[f64] {
                $crate::__private::flat::as_slice(self)
            }
            #[inline(always)]
            fn as_mut_slice(&mut self) -> &mut [f64] {
                $crate::__private::flat::as_mut_slice(self)
            }
            fn component_name(&self, index: usize) -> ::std::string::String {
                const NAMES: [&str; $len] = [$($name),*];
                NAMES.get(index).map_or_else(|| ::std::format!("#{index}"), |n| (*n).into())
            }
        }

        impl $state {
            /// Number of `f64` components.
            pub const LEN: usize = $len;

            /// The components as a vector, without copying.
            #[inline(always)]
            pub fn as_vector(&self) -> &$crate::__private::nalgebra::SVector<f64, $len> {
                $crate::__private::flat::as_vector(self)
            }

            /// The components as a mutable vector, without copying.
            #[inline(always)]
            pub fn as_vector_mut(&mut self) -> &mut $crate::__private::nalgebra::SVector<f64, $len> {
                $crate::__private::flat::as_vector_mut(self)
            }

            /// The state whose components are `vector`'s, in layout order.
            #[inline(always)]
            pub fn from_vector(vector: &$crate::__private::nalgebra::SVector<f64, $len>) -> Self {
                $crate::__private::flat::from_vector(vector)
            }

            /// The state with every component zero.
            pub fn zeros() -> Self {
                Self::from_vector(&$crate::__private::nalgebra::SVector::zeros())
            }
        }

        impl ::core::convert::From<$crate::__private::nalgebra::SVector<f64, $len>> for $state {
            fn from(vector: $crate::__private::nalgebra::SVector<f64, $len>) -> Self {
                Self::from_vector(&vector)
            }
        }

        impl ::core::convert::From<$state> for $crate::__private::nalgebra::SVector<f64, $len> {
            fn from(state: $state) -> Self {
                *state.as_vector()
            }
        }

        impl ::core::ops::Add for $state {
            type Output = Self;
            #[inline]
            fn add(self, rhs: Self) -> Self {
                Self::from_vector(&(self.as_vector() + rhs.as_vector()))
            }
        }

        impl ::core::ops::Sub for $state {
            type Output = Self;
            #[inline]
            fn sub(self, rhs: Self) -> Self {
                Self::from_vector(&(self.as_vector() - rhs.as_vector()))
            }
        }

        impl ::core::ops::Neg for $state {
            type Output = Self;
            #[inline]
            fn neg(self) -> Self {
                Self::from_vector(&(-self.as_vector()))
            }
        }

        impl ::core::ops::Mul<f64> for $state {
            type Output = Self;
            #[inline]
            fn mul(self, rhs: f64) -> Self {
                Self::from_vector(&(self.as_vector() * rhs))
            }
        }

        impl ::core::ops::Mul<$state> for f64 {
            type Output = $state;
            #[inline]
            fn mul(self, rhs: $state) -> $state {
                rhs * self
            }
        }

        impl ::core::ops::AddAssign for $state {
            #[inline]
            fn add_assign(&mut self, rhs: Self) {
                *self.as_vector_mut() += rhs.as_vector();
            }
        }

        impl ::core::ops::SubAssign for $state {
            #[inline]
            fn sub_assign(&mut self, rhs: Self) {
                *self.as_vector_mut() -= rhs.as_vector();
            }
        }
    };
}
