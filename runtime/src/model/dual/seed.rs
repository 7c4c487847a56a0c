//! Seeding the dual copy of a model's function and reading its column back, and the `as` casts
//! of its code.

use super::Dual;

/// What the dual copy of a model's function returns: its derivatives are a column of ∂f/∂y.
/// `#[system]` implements it for a first-order model's dual state.
pub trait Tangent {
    /// Passes each component's derivative to `out`, in layout order.
    fn tangent(&self, out: &mut impl FnMut(f64));
}

/// What the dual copy of a model's function takes: a state field's type over [`Dual`].
pub trait Seeded: Tangent + Sized {
    /// Its number of components.
    const LEN: usize;
    /// The value of components `values[..LEN]`, component `seed` with derivative one (none when
    /// `seed ≥ LEN`).
    fn seeded(values: &[f64], seed: usize) -> Self;
}

impl Tangent for Dual {
    #[inline(always)]
    fn tangent(&self, out: &mut impl FnMut(f64)) {
        out(self.eps);
    }
}

impl Seeded for Dual {
    const LEN: usize = 1;
    #[inline(always)]
    fn seeded(values: &[f64], seed: usize) -> Self {
        Dual::new(values[0], if seed == 0 { 1.0 } else { 0.0 })
    }
}

impl<T: Tangent, const N: usize> Tangent for [T; N] {
    #[inline(always)]
    fn tangent(&self, out: &mut impl FnMut(f64)) {
        self.iter().for_each(|x| x.tangent(out));
    }
}

impl<T: Seeded, const N: usize> Seeded for [T; N] {
    const LEN: usize = N * T::LEN;
    #[inline(always)]
    fn seeded(values: &[f64], seed: usize) -> Self {
        std::array::from_fn(|i| T::seeded(&values[i * T::LEN..], seed.wrapping_sub(i * T::LEN)))
    }
}

impl<const N: usize> Tangent for nalgebra::SVector<Dual, N> {
    #[inline(always)]
    fn tangent(&self, out: &mut impl FnMut(f64)) {
        self.iter().for_each(|x| x.tangent(out));
    }
}

impl<const N: usize> Seeded for nalgebra::SVector<Dual, N> {
    const LEN: usize = N;
    #[inline(always)]
    fn seeded(values: &[f64], seed: usize) -> Self {
        Self::from_fn(|i, _| Dual::seeded(&values[i..], seed.wrapping_sub(i)))
    }
}

/// The output of a second-order model with several velocity fields: a tuple.
macro_rules! tuples {
    ($(($($t:ident $i:tt),*)),*) => {$(
        impl<$($t: Tangent),*> Tangent for ($($t,)*) {
            #[inline(always)]
            fn tangent(&self, out: &mut impl FnMut(f64)) {
                $(self.$i.tangent(out);)*
            }
        }
    )*};
}

tuples!(
    (A 0, B 1),
    (A 0, B 1, C 2),
    (A 0, B 1, C 2, D 3),
    (A 0, B 1, C 2, D 3, E 4),
    (A 0, B 1, C 2, D 3, E 4, F 5)
);

/// `e as f64` in the dual copy of a model's function: a dual number keeps its derivative, any
/// other number is a constant.
pub trait ToDual {
    /// The number as a [`Dual`].
    fn to_dual(self) -> Dual;
}

impl ToDual for Dual {
    #[inline(always)]
    fn to_dual(self) -> Dual {
        self
    }
}

/// `e as T` for a primitive `T` in the dual copy of a model's function: a dual number's value
/// cast as `as` casts it (an index computed from the state, say).
pub trait DualCast<T> {
    /// `self as T`.
    fn cast(self) -> T;
}

impl<T: 'static + Copy> DualCast<T> for Dual
where
    f64: num_traits::AsPrimitive<T>,
{
    #[inline(always)]
    fn cast(self) -> T {
        num_traits::AsPrimitive::as_(self.re)
    }
}

macro_rules! primitives {
    ($($p:ty),*) => {$(
        impl ToDual for $p {
            #[inline(always)]
            #[allow(clippy::cast_lossless, clippy::cast_precision_loss, reason = "`as f64` as written")]
            fn to_dual(self) -> Dual {
                Dual::constant(self as f64)
            }
        }
        impl<T: 'static + Copy> DualCast<T> for $p
        where
            $p: num_traits::AsPrimitive<T>,
        {
            #[inline(always)]
            fn cast(self) -> T {
                num_traits::AsPrimitive::as_(self)
            }
        }
    )*};
}

primitives!(
    f64, f32, i8, i16, i32, i64, i128, isize, u8, u16, u32, u64, u128, usize
);
