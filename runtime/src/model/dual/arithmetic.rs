//! The operators of a dual number, with `f64` on either side: the sum, product and quotient
//! rules, and the remainder's.

use std::iter::{Product, Sum};
use std::ops::{
    Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign,
};

use nalgebra::allocator::Allocator;
use nalgebra::{DefaultAllocator, Dim, Matrix, OMatrix, Storage};

use super::Dual;

/// `slope · direction`, zero when the direction is: a constant operand contributes nothing even
/// where the slope is infinite or NaN, as the generated Jacobian leaves out a term whose
/// derivative is structurally zero.
#[inline(always)]
pub(super) fn term(slope: f64, direction: f64) -> f64 {
    if direction == 0.0 {
        0.0
    } else {
        slope * direction
    }
}

impl Neg for Dual {
    type Output = Dual;
    #[inline(always)]
    fn neg(self) -> Dual {
        Dual::new(-self.re, -self.eps)
    }
}

impl Add for Dual {
    type Output = Dual;
    #[inline(always)]
    fn add(self, other: Dual) -> Dual {
        Dual::new(self.re + other.re, self.eps + other.eps)
    }
}

impl Sub for Dual {
    type Output = Dual;
    #[inline(always)]
    fn sub(self, other: Dual) -> Dual {
        Dual::new(self.re - other.re, self.eps - other.eps)
    }
}

/// (ab)′ = a′b + ab′.
impl Mul for Dual {
    type Output = Dual;
    #[inline(always)]
    fn mul(self, other: Dual) -> Dual {
        Dual::new(
            self.re * other.re,
            term(other.re, self.eps) + term(self.re, other.eps),
        )
    }
}

/// (a/b)′ = a′/b − (a/b)·b′/b: finite wherever a/b is, where the textbook (a′b − ab′)/b²
/// overflows (eˣ/(1 + eˣ) at x = 709).
impl Div for Dual {
    type Output = Dual;
    #[inline(always)]
    fn div(self, other: Dual) -> Dual {
        let quotient = self.re / other.re;
        let first = if self.eps == 0.0 {
            0.0
        } else {
            self.eps / other.re
        };
        let second = if other.eps == 0.0 {
            0.0
        } else {
            quotient * (other.eps / other.re)
        };
        Dual::new(quotient, first - second)
    }
}

/// The remainder's derivative: a mod b = a − b·trunc(a/b), trunc's derivative zero.
impl Rem for Dual {
    type Output = Dual;
    #[inline(always)]
    fn rem(self, other: Dual) -> Dual {
        let quotient = (self.re / other.re).trunc();
        Dual::new(self.re % other.re, self.eps - term(quotient, other.eps))
    }
}

/// `Dual ∘ f64` and `f64 ∘ Dual` (the `f64` a constant), and the assigning forms, for each
/// operator.
macro_rules! mixed {
    ($($op:ident $method:ident $assign:ident $assign_method:ident),*) => {$(
        impl $op<f64> for Dual {
            type Output = Dual;
            #[inline(always)]
            fn $method(self, other: f64) -> Dual {
                $op::$method(self, Dual::constant(other))
            }
        }
        impl $op<Dual> for f64 {
            type Output = Dual;
            #[inline(always)]
            fn $method(self, other: Dual) -> Dual {
                $op::$method(Dual::constant(self), other)
            }
        }
        impl $assign for Dual {
            #[inline(always)]
            fn $assign_method(&mut self, other: Dual) {
                *self = $op::$method(*self, other);
            }
        }
        impl $assign<f64> for Dual {
            #[inline(always)]
            fn $assign_method(&mut self, other: f64) {
                *self = $op::$method(*self, other);
            }
        }
    )*};
}

mixed!(
    Add add AddAssign add_assign,
    Sub sub SubAssign sub_assign,
    Mul mul MulAssign mul_assign,
    Div div DivAssign div_assign,
    Rem rem RemAssign rem_assign
);

impl Sum for Dual {
    fn sum<I: Iterator<Item = Dual>>(iter: I) -> Dual {
        iter.fold(Dual::constant(0.0), Add::add)
    }
}

impl<'a> Sum<&'a Dual> for Dual {
    fn sum<I: Iterator<Item = &'a Dual>>(iter: I) -> Dual {
        iter.copied().sum()
    }
}

impl Product for Dual {
    fn product<I: Iterator<Item = Dual>>(iter: I) -> Dual {
        iter.fold(Dual::constant(1.0), Mul::mul)
    }
}

impl<'a> Product<&'a Dual> for Dual {
    fn product<I: Iterator<Item = &'a Dual>>(iter: I) -> Dual {
        iter.copied().product()
    }
}

/// `k * v` for a nalgebra matrix or vector `v` of dual numbers (nalgebra implements the scalar
/// on the left for primitive numbers only).
impl<R: Dim, C: Dim, S: Storage<Dual, R, C>> Mul<Matrix<Dual, R, C, S>> for Dual
where
    DefaultAllocator: Allocator<R, C>,
{
    type Output = OMatrix<Dual, R, C>;
    #[inline(always)]
    fn mul(self, matrix: Matrix<Dual, R, C, S>) -> Self::Output {
        matrix * self
    }
}

impl<'a, R: Dim, C: Dim, S: Storage<Dual, R, C>> Mul<&'a Matrix<Dual, R, C, S>> for Dual
where
    DefaultAllocator: Allocator<R, C>,
{
    type Output = OMatrix<Dual, R, C>;
    #[inline(always)]
    fn mul(self, matrix: &'a Matrix<Dual, R, C, S>) -> Self::Output {
        matrix * self
    }
}
