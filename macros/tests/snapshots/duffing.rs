impl Duffing {
    fn acceleration(&self) -> f64 {
        self.restoring(self.x) + Self::drag(self.b, self.v)
    }
    fn restoring(&self, x: f64) -> f64 {
        let k = self.k * 2.0;
        -k * x - self.c * x.powi(3)
    }
    fn drag(b: f64, v: f64) -> f64 {
        -b * v * v.abs()
    }
}
#[automatically_derived]
impl Duffing {
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
        self.restoring(__odyn_x) + Self::drag(self.b, __odyn_v)
    }
}
#[automatically_derived]
impl ::odyn::Model for Duffing {
    type State = DuffingState;
    type SecondOrder = Self;
    const NAME: &'static str = "Duffing";
    const DEFAULT_METHOD: ::odyn::Method = ::odyn::Method::Rodas5P;
    const DEFAULT_DT: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_RTOL: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_ATOL: ::core::option::Option<f64> = ::core::option::Option::None;
    #[inline]
    fn state(&self) -> DuffingState {
        DuffingState {
            x: self.x,
            v: self.v,
        }
    }
    #[inline(always)]
    fn derivative(&self, t: f64, y: &DuffingState, dydt: &mut DuffingState) {
        <Self as ::odyn::SecondOrder>::acceleration(self, t, y, dydt);
        dydt.x = y.v;
    }
    #[inline]
    fn energy(&self, state: &DuffingState) -> ::core::option::Option<f64> {
        ::core::option::Option::None
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
impl ::odyn::__private::Sealed for Duffing {}
const _: () = {
    let _ = <Duffing as ::odyn::Model>::DEFAULT_DT;
    let _ = <Duffing as ::odyn::Model>::DEFAULT_RTOL;
    let _ = <Duffing as ::odyn::Model>::DEFAULT_ATOL;
};
#[automatically_derived]
impl ::odyn::SecondOrder for Duffing {
    const READS_VELOCITY: bool = true;
    #[inline(always)]
    fn acceleration(&self, t: f64, y: &DuffingState, accel: &mut DuffingState) {
        let a = self.__odyn_acceleration(t, y.x, y.v);
        accel.v = a;
    }
}
const _: () = {
    let _ = <Duffing>::acceleration;
};
#[automatically_derived]
impl Duffing {
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
        let mut __odyn_p0: f64 = f64::NAN;
        let mut __odyn_p1: f64 = f64::NAN;
        {
            __odyn_p0 = self.k;
            let k = self.k * 2.0;
            __odyn_p1 = self.c;
        }
        let __odyn_p2: f64 = self.b;
        let __odyn_e3: f64 = __odyn_p0 * (2f64);
        let __odyn_e4: f64 = -__odyn_e3;
        let __odyn_e13: f64 = -__odyn_p2;
        let __odyn_e14: f64 = __odyn_v * __odyn_e13;
        let __odyn_e15: f64 = __odyn_v.abs();
        let __odyn_e21: f64 = __odyn_x.powi(2i32);
        let __odyn_e22: f64 = (3f64) * __odyn_e21;
        let __odyn_e23: f64 = __odyn_p1 * __odyn_e22;
        let __odyn_e24: f64 = -__odyn_e23;
        let __odyn_e25: f64 = __odyn_e4 + __odyn_e24;
        let __odyn_e26: f64 = __odyn_v.signum();
        let __odyn_e27: f64 = __odyn_e13 * __odyn_e15;
        let __odyn_e28: f64 = __odyn_e14 * __odyn_e26;
        let __odyn_e29: f64 = __odyn_e27 + __odyn_e28;
        *__odyn_jac = ::odyn::__private::nalgebra::SMatrix::from_array_storage(
            ::odyn::__private::nalgebra::ArrayStorage([
                [0.0f64, __odyn_e25],
                [(1f64), __odyn_e29],
            ]),
        );
    }
}
#[automatically_derived]
impl ::odyn::Jacobian for Duffing {
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
        _: &DuffingState,
    ) -> ::odyn::__private::nalgebra::SMatrix<f64, 2, 2> {
        ::odyn::__private::nalgebra::SMatrix::<f64, 2, 2>::zeros()
    }
    #[inline]
    fn jacobian(
        &self,
        t: f64,
        y: &DuffingState,
        jacobian: &mut ::odyn::__private::nalgebra::SMatrix<f64, 2, 2>,
    ) {
        self.__odyn_jacobian(t, y.x, y.v, jacobian)
    }
    /// The model's function does not read the time: ∂f/∂t = 0.
    const TIME_DEPENDENT: bool = false;
    #[inline]
    fn time_derivative(&self, _: f64, _: &DuffingState, dfdt: &mut DuffingState) {
        ::odyn::State::as_mut_slice(dfdt).fill(0.0);
    }
}
