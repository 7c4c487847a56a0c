impl Kepler {
    fn acceleration(&self) -> Vector2<f64> {
        let r = self.r;
        -self.gm * r / r.norm().powi(3)
    }
}
#[automatically_derived]
impl Kepler {
    #[doc(hidden)]
    #[inline(always)]
    #[allow(
        unused_variables,
        unused_assignments,
        unused_parens,
        non_snake_case,
        clippy::all
    )]
    fn __odyn_acceleration(
        &self,
        _: f64,
        __odyn_r: &::odyn::__private::nalgebra::SVector<f64, 2>,
        __odyn_v: &::odyn::__private::nalgebra::SVector<f64, 2>,
    ) -> Vector2<f64> {
        let r = (*__odyn_r);
        -self.gm * r / r.norm().powi(3)
    }
}
#[automatically_derived]
impl ::odyn::Model for Kepler {
    type State = KeplerState;
    type SecondOrder = Self;
    const NAME: &'static str = "Kepler";
    const DEFAULT_METHOD: ::odyn::Method = ::odyn::Method::Leapfrog;
    const DEFAULT_DT: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_RTOL: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_ATOL: ::core::option::Option<f64> = ::core::option::Option::None;
    #[inline]
    fn state(&self) -> KeplerState {
        KeplerState {
            r: self.r,
            v: self.v,
        }
    }
    #[inline(always)]
    fn derivative(&self, t: f64, y: &KeplerState, dydt: &mut KeplerState) {
        <Self as ::odyn::SecondOrder>::acceleration(self, t, y, dydt);
        dydt.r = y.v;
    }
    #[inline]
    fn energy(&self, state: &KeplerState) -> ::core::option::Option<f64> {
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
impl ::odyn::__private::Sealed for Kepler {}
const _: () = {
    let _ = <Kepler as ::odyn::Model>::DEFAULT_DT;
    let _ = <Kepler as ::odyn::Model>::DEFAULT_RTOL;
    let _ = <Kepler as ::odyn::Model>::DEFAULT_ATOL;
};
#[automatically_derived]
impl ::odyn::SecondOrder for Kepler {
    const READS_VELOCITY: bool = false;
    #[inline(always)]
    fn acceleration(&self, t: f64, y: &KeplerState, accel: &mut KeplerState) {
        let a = self.__odyn_acceleration(t, &y.r, &y.v);
        accel.v = a;
    }
}
const _: () = {
    let _ = <Kepler>::acceleration;
};
#[automatically_derived]
impl Kepler {
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
        __odyn_r: &::odyn::__private::nalgebra::SVector<f64, 2>,
        __odyn_v: &::odyn::__private::nalgebra::SVector<f64, 2>,
        __odyn_jac: &mut ::odyn::__private::nalgebra::SMatrix<f64, 4, 4>,
    ) {
        let __odyn_p0: f64 = self.gm;
        let __odyn_e3: f64 = -__odyn_p0;
        let __odyn_e4: f64 = __odyn_r[0usize] * __odyn_e3;
        let __odyn_e5: f64 = __odyn_r[1usize] * __odyn_e3;
        let __odyn_e7: f64 = __odyn_r[0usize] * __odyn_r[0usize];
        let __odyn_e8: f64 = __odyn_r[1usize] * __odyn_r[1usize];
        let __odyn_e9: f64 = __odyn_e7 + __odyn_e8;
        let __odyn_e10: f64 = __odyn_e9.sqrt();
        let __odyn_e11: f64 = __odyn_e10.powi(3i32);
        let __odyn_e12: f64 = __odyn_e4 / __odyn_e11;
        let __odyn_e13: f64 = __odyn_e5 / __odyn_e11;
        let __odyn_e17: f64 = __odyn_r[0usize] + __odyn_r[0usize];
        let __odyn_e19: f64 = __odyn_e10 * (2f64);
        let __odyn_e20: f64 = (1f64) / __odyn_e19;
        let __odyn_e21: f64 = __odyn_e17 * __odyn_e20;
        let __odyn_e23: f64 = __odyn_e10.powi(2i32);
        let __odyn_e24: f64 = (3f64) * __odyn_e23;
        let __odyn_e25: f64 = __odyn_e21 * __odyn_e24;
        let __odyn_e26: f64 = __odyn_e3 / __odyn_e11;
        let __odyn_e27: f64 = __odyn_e25 / __odyn_e11;
        let __odyn_e28: f64 = __odyn_e12 * __odyn_e27;
        let __odyn_e29: f64 = -__odyn_e28;
        let __odyn_e30: f64 = __odyn_e26 + __odyn_e29;
        let __odyn_e31: f64 = __odyn_r[1usize] + __odyn_r[1usize];
        let __odyn_e32: f64 = __odyn_e20 * __odyn_e31;
        let __odyn_e33: f64 = __odyn_e24 * __odyn_e32;
        let __odyn_e34: f64 = __odyn_e33 / __odyn_e11;
        let __odyn_e35: f64 = __odyn_e12 * __odyn_e34;
        let __odyn_e36: f64 = -__odyn_e35;
        let __odyn_e37: f64 = __odyn_e13 * __odyn_e27;
        let __odyn_e38: f64 = -__odyn_e37;
        let __odyn_e39: f64 = __odyn_e13 * __odyn_e34;
        let __odyn_e40: f64 = -__odyn_e39;
        let __odyn_e41: f64 = __odyn_e26 + __odyn_e40;
        *__odyn_jac = ::odyn::__private::nalgebra::SMatrix::from_array_storage(
            ::odyn::__private::nalgebra::ArrayStorage([
                [0.0f64, 0.0f64, __odyn_e30, __odyn_e38],
                [0.0f64, 0.0f64, __odyn_e36, __odyn_e41],
                [(1f64), 0.0f64, 0.0f64, 0.0f64],
                [0.0f64, (1f64), 0.0f64, 0.0f64],
            ]),
        );
    }
}
#[automatically_derived]
impl ::odyn::Jacobian for Kepler {
    type Matrix = ::odyn::__private::nalgebra::SMatrix<f64, 4, 4>;
    ///The 6 structural non-zeros of ∂f/∂y, derived by `#[system]` from the model's code.
    const NONZEROS: &'static [(usize, usize)] = &[
        (0usize, 2usize),
        (1usize, 3usize),
        (2usize, 0usize),
        (2usize, 1usize),
        (3usize, 0usize),
        (3usize, 1usize),
    ];
    #[inline]
    fn jacobian_matrix(
        &self,
        _: &KeplerState,
    ) -> ::odyn::__private::nalgebra::SMatrix<f64, 4, 4> {
        ::odyn::__private::nalgebra::SMatrix::<f64, 4, 4>::zeros()
    }
    #[inline]
    fn jacobian(
        &self,
        t: f64,
        y: &KeplerState,
        jacobian: &mut ::odyn::__private::nalgebra::SMatrix<f64, 4, 4>,
    ) {
        self.__odyn_jacobian(t, &y.r, &y.v, jacobian)
    }
    /// The model's function does not read the time: ∂f/∂t = 0.
    const TIME_DEPENDENT: bool = false;
    #[inline]
    fn time_derivative(&self, _: f64, _: &KeplerState, dfdt: &mut KeplerState) {
        ::odyn::State::as_mut_slice(dfdt).fill(0.0);
    }
}
