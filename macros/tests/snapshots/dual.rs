impl Tabled {
    fn derivative(&self, t: f64) -> TabledState {
        let i = (self.x.abs() * 2.0).min(2.0) as usize;
        TabledState {
            x: self.table[i] * self.y[0] + t,
            y: Self::pair(self.k, self.x),
        }
    }
    fn pair(k: f64, x: f64) -> [f64; 2] {
        [-k * x, f64::max(x, 0.0)]
    }
}
#[automatically_derived]
impl Tabled {
    #[doc(hidden)]
    #[inline(always)]
    #[allow(
        unused_variables,
        unused_assignments,
        unused_parens,
        non_snake_case,
        clippy::all
    )]
    fn __odyn_derivative(
        &self,
        t: f64,
        __odyn_x: f64,
        __odyn_y: &[f64; 2],
    ) -> TabledState {
        let i = (__odyn_x.abs() * 2.0).min(2.0) as usize;
        TabledState {
            x: self.table[i] * (*__odyn_y)[0] + t,
            y: Self::pair(self.k, __odyn_x),
        }
    }
}
#[automatically_derived]
impl ::odyn::Model for Tabled {
    type State = TabledState;
    type SecondOrder = ::odyn::__private::Unavailable<Self>;
    const NAME: &'static str = "Tabled";
    const DEFAULT_METHOD: ::odyn::Method = ::odyn::Method::Rk4;
    const DEFAULT_DT: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_RTOL: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_ATOL: ::core::option::Option<f64> = ::core::option::Option::None;
    #[inline]
    fn state(&self) -> TabledState {
        TabledState {
            x: self.x,
            y: self.y,
        }
    }
    #[inline(always)]
    fn derivative(&self, t: f64, y: &TabledState, dydt: &mut TabledState) {
        *dydt = self.__odyn_derivative(t, y.x, &y.y);
    }
    #[inline]
    fn energy(&self, state: &TabledState) -> ::core::option::Option<f64> {
        ::core::option::Option::None
    }
    #[inline(always)]
    fn as_second_order(&self) -> ::core::option::Option<&Self::SecondOrder> {
        ::core::option::Option::None
    }
    type Jacobian = Self;
    #[inline(always)]
    fn as_jacobian(&self) -> ::core::option::Option<&Self> {
        ::core::option::Option::Some(self)
    }
}
#[automatically_derived]
impl ::odyn::__private::Sealed for Tabled {}
const _: () = {
    let _ = <Tabled as ::odyn::Model>::DEFAULT_DT;
    let _ = <Tabled as ::odyn::Model>::DEFAULT_RTOL;
    let _ = <Tabled as ::odyn::Model>::DEFAULT_ATOL;
};
const _: () = {
    let _ = <Tabled>::derivative;
};
#[doc(hidden)]
#[allow(non_camel_case_types)]
struct __TabledStateDual {
    x: ::odyn::Dual,
    y: [::odyn::Dual; 2],
}
#[automatically_derived]
impl ::odyn::__private::Tangent for __TabledStateDual {
    #[inline(always)]
    fn tangent(&self, out: &mut impl FnMut(f64)) {
        ::odyn::__private::Tangent::tangent(&self.x, out);
        ::odyn::__private::Tangent::tangent(&self.y, out);
    }
}
#[automatically_derived]
impl Tabled {
    #[doc(hidden)]
    #[inline]
    #[allow(
        unused_variables,
        unused_assignments,
        unused_parens,
        non_snake_case,
        clippy::all
    )]
    fn __odyn_dual_derivative(
        &self,
        __odyn_parameter: usize,
        t: ::odyn::Dual,
        __odyn_x: ::odyn::Dual,
        __odyn_y: &[::odyn::Dual; 2],
    ) -> __TabledStateDual {
        #[allow(unused_imports)]
        use ::odyn::__private::nalgebra::{ComplexField as _, RealField as _};
        {
            let i = ::odyn::__private::DualCast::<
                usize,
            >::cast(
                (__odyn_x.abs() * ::odyn::Dual::constant(2.0))
                    .min(::odyn::Dual::constant(2.0)),
            );
            __TabledStateDual {
                x: ::odyn::Dual::constant(self.table[i]) * (*__odyn_y)[0] + t,
                y: Self::__odyn_dual_pair(
                    __odyn_parameter,
                    ::odyn::Dual::constant(self.k),
                    __odyn_x,
                ),
            }
        }
    }
    /// f over dual numbers at the state `values`, component `seed` of the state or
    /// `#[param]` number `parameter` seeded.
    #[doc(hidden)]
    #[inline]
    #[allow(unused_assignments, clippy::all)]
    fn __odyn_dual_at(
        &self,
        t: ::odyn::Dual,
        values: &[f64],
        seed: usize,
        parameter: usize,
    ) -> __TabledStateDual {
        let mut offset = 0usize;
        let __odyn_x = <::odyn::Dual as ::odyn::__private::Seeded>::seeded(
            &values[offset..],
            seed.wrapping_sub(offset),
        );
        offset += <::odyn::Dual as ::odyn::__private::Seeded>::LEN;
        let __odyn_y = <[::odyn::Dual; 2] as ::odyn::__private::Seeded>::seeded(
            &values[offset..],
            seed.wrapping_sub(offset),
        );
        offset += <[::odyn::Dual; 2] as ::odyn::__private::Seeded>::LEN;
        self.__odyn_dual_derivative(parameter, t, __odyn_x, &__odyn_y)
    }
    #[doc(hidden)]
    #[allow(clippy::all, unused_parens)]
    fn __odyn_dual_pair(
        __odyn_parameter: usize,
        k: ::odyn::Dual,
        x: ::odyn::Dual,
    ) -> [::odyn::Dual; 2] {
        #[allow(unused_imports)]
        use ::odyn::__private::nalgebra::{ComplexField as _, RealField as _};
        [-k * x, ::odyn::Dual::max(x, ::odyn::Dual::constant(0.0))]
    }
}
#[automatically_derived]
impl ::odyn::Jacobian for Tabled {
    type Matrix = ::odyn::__private::nalgebra::SMatrix<f64, 3, 3>;
    /// Not known: the Jacobian is taken by forward-mode differentiation of the code.
    const NONZEROS: &'static [(usize, usize)] = &[];
    #[inline]
    fn jacobian_matrix(
        &self,
        state: &TabledState,
    ) -> ::odyn::__private::nalgebra::SMatrix<f64, 3, 3> {
        ::odyn::__private::nalgebra::SMatrix::<f64, 3, 3>::zeros()
    }
    /// ∂f/∂y column by column, one dual evaluation of f each, exact to rounding.
    fn jacobian(
        &self,
        t: f64,
        y: &TabledState,
        jacobian: &mut ::odyn::__private::nalgebra::SMatrix<f64, 3, 3>,
    ) {
        let values = ::odyn::State::as_slice(y);
        let time = ::odyn::Dual::constant(t);
        for column in 0..values.len() {
            let out = self.__odyn_dual_at(time, values, column, usize::MAX);
            let start = 0;
            for row in 0..start {
                let value = if column == start + row { 1.0 } else { 0.0 };
                jacobian[(row, column)] = value;
            }
            let mut row = start;
            ::odyn::__private::Tangent::tangent(
                &out,
                &mut |value| {
                    jacobian[(row, column)] = value;
                    row += 1;
                },
            );
        }
    }
    /// True: the model's function reads the time; ∂f/∂t by one dual evaluation.
    const TIME_DEPENDENT: bool = true;
    fn time_derivative(&self, t: f64, y: &TabledState, dfdt: &mut TabledState) {
        let out = self
            .__odyn_dual_at(
                ::odyn::Dual::new(t, 1.0),
                ::odyn::State::as_slice(y),
                usize::MAX,
                usize::MAX,
            );
        let dfdt = ::odyn::State::as_mut_slice(dfdt);
        let mut row = 0;
        dfdt[..row].fill(0.0);
        ::odyn::__private::Tangent::tangent(
            &out,
            &mut |value| {
                dfdt[row] = value;
                row += 1;
            },
        );
    }
}
