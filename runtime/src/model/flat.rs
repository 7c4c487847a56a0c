//! Safe views of fixed-size generated states as `f64` slices and `nalgebra` vectors, and the
//! macro that gives a generated state struct its `State` impl.

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

/// `a` with `op` applied to each pair of components of `a` and `b`: the arithmetic of generated
/// states.
#[inline]
pub fn zip<T: FlatState>(mut a: T, b: &T, op: impl Fn(f64, f64) -> f64) -> T {
    for (x, y) in as_mut_slice(&mut a).iter_mut().zip(as_slice(b)) {
        *x = op(*x, *y);
    }
    a
}

/// How a field of a const-generic model's state is laid out, for its components' names.
#[derive(Clone, Copy, Debug)]
pub enum FieldLayout {
    /// `f64`: one component, named as the field (`k`).
    Scalar,
    /// `[f64; N]` or `SVector<f64, N>`: `x[0]`, `x[1]`, …
    Flat(usize),
    /// `[[f64; M]; N]` or `[SVector<f64, M>; N]`: `r[0][0]`, `r[0][1]`, …, row after row.
    Rows(usize, usize),
}

impl FieldLayout {
    fn len(self) -> usize {
        match self {
            FieldLayout::Scalar => 1,
            FieldLayout::Flat(n) => n,
            FieldLayout::Rows(n, m) => n * m,
        }
    }
}

/// The name of component `index` of a state whose fields are `fields`, in layout order
/// (`x[2]`), or `#index` past its end: `State::component_name` of a const-generic model, whose
/// names the macro cannot list.
pub fn component_name(fields: &[(&str, FieldLayout)], index: usize) -> String {
    let mut offset = 0;
    for &(name, layout) in fields {
        let i = index - offset;
        if i < layout.len() {
            return match layout {
                FieldLayout::Scalar => name.to_owned(),
                FieldLayout::Flat(_) => format!("{name}[{i}]"),
                FieldLayout::Rows(_, m) => format!("{name}[{}][{}]", i / m, i % m),
            };
        }
        offset += layout.len();
    }
    format!("#{index}")
}

/// Implements [`State`](crate::State), [`FlatState`] and arithmetic for the state struct of a
/// const-generic model: `generic_flat_state!(Name[N, M], LEN, [("x", FieldLayout::Flat(N)), …],
/// zero-value)`. As [`__flat_state`] without the `SVector` views, whose length stable Rust cannot
/// name. Not a public API.
#[doc(hidden)]
#[macro_export]
macro_rules! __generic_flat_state {
    ($state:ident [$($p:ident),*], $len:expr, [$($field:expr),*], $zero:expr) => {
        // SAFETY: `#[system]` generates `$state` as `#[repr(C)]` with only `f64`, `[f64; N]`,
        // `SVector<f64, N>` and arrays of those fields totalling `$len` components; `as_slice`
        // and `as_mut_slice` assert the size for every instantiation.
        unsafe impl<$(const $p: usize),*> $crate::__private::FlatState for $state<$($p),*> {
            const LEN: usize = $len;
        }

        impl<$(const $p: usize),*> $crate::State for $state<$($p),*> {
            #[inline(always)]
            fn as_slice(&self) -> &[f64] {
                $crate::__private::flat::as_slice(self)
            }
            #[inline(always)]
            fn as_mut_slice(&mut self) -> &mut [f64] {
                $crate::__private::flat::as_mut_slice(self)
            }
            fn component_name(&self, index: usize) -> ::std::string::String {
                $crate::__private::component_name(&[$($field),*], index)
            }
        }

        impl<$(const $p: usize),*> $state<$($p),*> {
            /// Number of `f64` components.
            pub const LEN: usize = $len;

            /// The state with every component zero.
            pub fn zeros() -> Self {
                $zero
            }
        }

        $crate::__private::state_arithmetic!($state [$($p),*]);
    };
}

/// Implements [`State`](crate::State), [`FlatState`], conversions and arithmetic for a state struct
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

        $crate::__private::state_arithmetic!($state []);
    };
}

/// Implements `+`, `−`, unary `−`, `× f64`, `f64 ×`, `+=` and `−=` component by component for a
/// generated state struct, generic over the const parameters in brackets (none for a concrete
/// model): `state_arithmetic!(ChainState [N])`. Not a public API.
#[doc(hidden)]
#[macro_export]
macro_rules! __state_arithmetic {
    ($state:ident [$($p:ident),*]) => {
        impl<$(const $p: usize),*> ::core::ops::Add for $state<$($p),*> {
            type Output = Self;
            #[inline]
            fn add(self, rhs: Self) -> Self {
                $crate::__private::flat::zip(self, &rhs, |a, b| a + b)
            }
        }

        impl<$(const $p: usize),*> ::core::ops::Sub for $state<$($p),*> {
            type Output = Self;
            #[inline]
            fn sub(self, rhs: Self) -> Self {
                $crate::__private::flat::zip(self, &rhs, |a, b| a - b)
            }
        }

        impl<$(const $p: usize),*> ::core::ops::Neg for $state<$($p),*> {
            type Output = Self;
            #[inline]
            fn neg(self) -> Self {
                $crate::__private::flat::zip(self, &self, |a, _| -a)
            }
        }

        impl<$(const $p: usize),*> ::core::ops::Mul<f64> for $state<$($p),*> {
            type Output = Self;
            #[inline]
            fn mul(self, rhs: f64) -> Self {
                $crate::__private::flat::zip(self, &self, |a, _| a * rhs)
            }
        }

        impl<$(const $p: usize),*> ::core::ops::Mul<$state<$($p),*>> for f64 {
            type Output = $state<$($p),*>;
            #[inline]
            fn mul(self, rhs: $state<$($p),*>) -> $state<$($p),*> {
                rhs * self
            }
        }

        impl<$(const $p: usize),*> ::core::ops::AddAssign for $state<$($p),*> {
            #[inline]
            fn add_assign(&mut self, rhs: Self) {
                *self = *self + rhs;
            }
        }

        impl<$(const $p: usize),*> ::core::ops::SubAssign for $state<$($p),*> {
            #[inline]
            fn sub_assign(&mut self, rhs: Self) {
                *self = *self - rhs;
            }
        }
    };
}
