impl Spring {
    fn acceleration(&self) -> f64 {
        (-self.k * self.x - self.b * self.v) / self.m
    }
    fn energy(&self) -> f64 {
        0.5 * self.m * self.v * self.v + 0.5 * self.k * self.x * self.x
    }
}
#[automatically_derived]
impl Spring {
    #[doc(hidden)]
    #[inline(always)]
    #[allow(
        unused_variables,
        unused_assignments,
        unused_parens,
        non_snake_case,
        clippy::all
    )]
    fn __odyn_acceleration(&self, _: f64, __odyn_x: f64, __odyn_v: f64) -> f64 {
        (-self.k * __odyn_x - self.b * __odyn_v) / self.m
    }
    #[doc(hidden)]
    #[inline(always)]
    #[allow(
        unused_variables,
        unused_assignments,
        unused_parens,
        non_snake_case,
        clippy::all
    )]
    fn __odyn_energy(&self, __odyn_x: f64, __odyn_v: f64) -> f64 {
        0.5 * self.m * __odyn_v * __odyn_v + 0.5 * self.k * __odyn_x * __odyn_x
    }
}
#[automatically_derived]
impl ::odyn::Model for Spring {
    type State = SpringState;
    type SecondOrder = Self;
    const NAME: &'static str = "Spring";
    const DEFAULT_METHOD: ::odyn::Method = ::odyn::Method::SymplecticEuler;
    const DEFAULT_DT: ::core::option::Option<f64> = ::core::option::Option::Some({
        let value = (0.016) as f64;
        ::core::assert!(
            value.is_finite() && value > 0.0,
            "`dt` in `#[system]` must be finite and positive"
        );
        value
    });
    const DEFAULT_RTOL: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_ATOL: ::core::option::Option<f64> = ::core::option::Option::None;
    #[inline]
    fn state(&self) -> SpringState {
        SpringState {
            x: self.x,
            v: self.v,
        }
    }
    #[inline(always)]
    fn derivative(&self, t: f64, y: &SpringState, dydt: &mut SpringState) {
        <Self as ::odyn::SecondOrder>::acceleration(self, t, y, dydt);
        dydt.x = y.v;
    }
    #[inline]
    fn energy(&self, state: &SpringState) -> ::core::option::Option<f64> {
        ::core::option::Option::Some(self.__odyn_energy(state.x, state.v))
    }
    #[inline(always)]
    fn as_second_order(&self) -> ::core::option::Option<&Self> {
        ::core::option::Option::Some(self)
    }
    type Jacobian = Self;
    #[inline(always)]
    fn as_jacobian(&self) -> ::core::option::Option<&Self> {
        ::core::option::Option::Some(self)
    }
}
#[automatically_derived]
impl ::odyn::__private::Sealed for Spring {}
const _: () = {
    let _ = <Spring as ::odyn::Model>::DEFAULT_DT;
    let _ = <Spring as ::odyn::Model>::DEFAULT_RTOL;
    let _ = <Spring as ::odyn::Model>::DEFAULT_ATOL;
};
#[automatically_derived]
impl ::odyn::SecondOrder for Spring {
    const READS_VELOCITY: bool = true;
    #[inline(always)]
    fn acceleration(&self, t: f64, y: &SpringState, accel: &mut SpringState) {
        let a = self.__odyn_acceleration(t, y.x, y.v);
        accel.v = a;
    }
}
const _: () = {
    let _ = <Spring>::acceleration;
    let _ = <Spring>::energy;
};
#[automatically_derived]
impl Spring {
    #[doc(hidden)]
    #[inline]
    #[allow(
        unused_variables,
        unused_assignments,
        unused_mut,
        unused_parens,
        non_snake_case,
        clippy::all
    )]
    fn __odyn_jacobian(
        &self,
        _: f64,
        __odyn_x: f64,
        __odyn_v: f64,
        __odyn_jac: &mut ::odyn::__private::nalgebra::SMatrix<f64, 2, 2>,
    ) {
        let __odyn_p0: f64 = self.k;
        let __odyn_p1: f64 = self.b;
        let __odyn_p2: f64 = self.m;
        let __odyn_e1: f64 = -__odyn_p0;
        let __odyn_e13: f64 = __odyn_e1 / __odyn_p2;
        let __odyn_e14: f64 = -__odyn_p1;
        let __odyn_e15: f64 = __odyn_e14 / __odyn_p2;
        *__odyn_jac = ::odyn::__private::nalgebra::SMatrix::from_array_storage(
            ::odyn::__private::nalgebra::ArrayStorage([
                [0.0f64, __odyn_e13],
                [(1f64), __odyn_e15],
            ]),
        );
    }
}
#[automatically_derived]
impl ::odyn::Jacobian for Spring {
    type Matrix = ::odyn::__private::nalgebra::SMatrix<f64, 2, 2>;
    ///The 3 structural non-zeros of ∂f/∂y, derived by `#[system]` from the model's code.
    const NONZEROS: &'static [(usize, usize)] = &[
        (0usize, 1usize),
        (1usize, 0usize),
        (1usize, 1usize),
    ];
    #[inline]
    fn jacobian_matrix(
        &self,
        _: &SpringState,
    ) -> ::odyn::__private::nalgebra::SMatrix<f64, 2, 2> {
        ::odyn::__private::nalgebra::SMatrix::<f64, 2, 2>::zeros()
    }
    #[inline]
    fn jacobian(
        &self,
        t: f64,
        y: &SpringState,
        jacobian: &mut ::odyn::__private::nalgebra::SMatrix<f64, 2, 2>,
    ) {
        self.__odyn_jacobian(t, y.x, y.v, jacobian)
    }
    /// The model's function does not read the time: ∂f/∂t = 0.
    const TIME_DEPENDENT: bool = false;
    #[inline]
    fn time_derivative(&self, _: f64, _: &SpringState, dfdt: &mut SpringState) {
        ::odyn::State::as_mut_slice(dfdt).fill(0.0);
    }
}
