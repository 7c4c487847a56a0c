impl Decay {
    fn derivative(&self, t: f64) -> DecayState {
        let rate = if self.c > 0.0 { self.k * self.y } else { self.k };
        DecayState {
            y: -rate + (self.c * t).sin(),
            z: rate - self.c * self.z * self.z,
        }
    }
}
#[automatically_derived]
impl Decay {
    #[doc(hidden)]
    #[inline(always)]
    #[allow(
        unused_variables,
        unused_assignments,
        unused_parens,
        non_snake_case,
        clippy::all
    )]
    fn __odyn_derivative(&self, t: f64, __odyn_y: f64, __odyn_z: f64) -> DecayState {
        let rate = if self.c > 0.0 { self.k * __odyn_y } else { self.k };
        DecayState {
            y: -rate + ::odyn::math::Transcendental::sin(self.c * t),
            z: rate - self.c * __odyn_z * __odyn_z,
        }
    }
}
#[automatically_derived]
impl ::odyn::Model for Decay {
    type State = DecayState;
    type SecondOrder = ::odyn::__private::Unavailable<Self>;
    const NAME: &'static str = "Decay";
    const DEFAULT_METHOD: ::odyn::Method = ::odyn::Method::Rodas5P;
    const DEFAULT_DT: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_RTOL: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_ATOL: ::core::option::Option<f64> = ::core::option::Option::None;
    #[inline]
    fn state(&self) -> DecayState {
        DecayState { y: self.y, z: self.z }
    }
    #[inline(always)]
    fn derivative(&self, t: f64, y: &DecayState, dydt: &mut DecayState) {
        *dydt = self.__odyn_derivative(t, y.y, y.z);
    }
    #[inline]
    fn energy(&self, state: &DecayState) -> ::core::option::Option<f64> {
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
impl ::odyn::__private::Sealed for Decay {}
const _: () = {
    let _ = <Decay as ::odyn::Model>::DEFAULT_DT;
    let _ = <Decay as ::odyn::Model>::DEFAULT_RTOL;
    let _ = <Decay as ::odyn::Model>::DEFAULT_ATOL;
};
const _: () = {
    let _ = <Decay>::derivative;
};
#[automatically_derived]
impl Decay {
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
        t: f64,
        __odyn_y: f64,
        __odyn_z: f64,
        __odyn_jac: &mut ::odyn::__private::nalgebra::SMatrix<f64, 2, 2>,
    ) {
        let __odyn_time: f64 = t;
        let mut __odyn_s0: usize = usize::MAX;
        let mut __odyn_p1: f64 = f64::NAN;
        if self.c > 0.0 {
            __odyn_p1 = self.k;
            __odyn_s0 = 0usize;
        } else {
            __odyn_s0 = 1usize;
        }
        let __odyn_p4: f64 = self.c;
        let __odyn_e14: f64 = __odyn_p4 * __odyn_z;
        let __odyn_e20: f64 = if __odyn_s0 == 0usize { __odyn_p1 } else { (0f64) };
        let __odyn_e21: f64 = -__odyn_e20;
        let __odyn_e22: f64 = __odyn_e14 + __odyn_e14;
        let __odyn_e23: f64 = -__odyn_e22;
        *__odyn_jac = ::odyn::__private::nalgebra::SMatrix::from_array_storage(
            ::odyn::__private::nalgebra::ArrayStorage([
                [__odyn_e21, __odyn_e20],
                [0.0f64, __odyn_e23],
            ]),
        );
    }
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
    fn __odyn_time_derivative(
        &self,
        t: f64,
        __odyn_y: f64,
        __odyn_z: f64,
        __odyn_dfdt: &mut DecayState,
    ) {
        let __odyn_time: f64 = t;
        let mut __odyn_s0: usize = usize::MAX;
        if self.c > 0.0 {
            __odyn_s0 = 0usize;
        } else {
            __odyn_s0 = 1usize;
        }
        let __odyn_p3: f64 = self.c;
        let __odyn_e9: f64 = __odyn_p3 * __odyn_time;
        let __odyn_e24: f64 = ::odyn::math::Transcendental::cos(__odyn_e9);
        let __odyn_e25: f64 = __odyn_p3 * __odyn_e24;
        let out = ::odyn::State::as_mut_slice(__odyn_dfdt);
        out.fill(0.0);
        out[0usize] = __odyn_e25;
    }
}
#[automatically_derived]
impl ::odyn::Jacobian for Decay {
    type Matrix = ::odyn::__private::nalgebra::SMatrix<f64, 2, 2>;
    ///The 3 structural non-zeros of ∂f/∂y, derived by `#[system]` from the model's code.
    const NONZEROS: &'static [(usize, usize)] = &[
        (0usize, 0usize),
        (1usize, 0usize),
        (1usize, 1usize),
    ];
    #[inline]
    fn jacobian_matrix(
        &self,
        _: &DecayState,
    ) -> ::odyn::__private::nalgebra::SMatrix<f64, 2, 2> {
        ::odyn::__private::nalgebra::SMatrix::<f64, 2, 2>::zeros()
    }
    #[inline]
    fn jacobian(
        &self,
        t: f64,
        y: &DecayState,
        jacobian: &mut ::odyn::__private::nalgebra::SMatrix<f64, 2, 2>,
    ) {
        self.__odyn_jacobian(t, y.y, y.z, jacobian)
    }
    const TIME_DEPENDENT: bool = true;
    #[inline]
    fn time_derivative(&self, t: f64, y: &DecayState, dfdt: &mut DecayState) {
        self.__odyn_time_derivative(t, y.y, y.z, dfdt)
    }
}
#[automatically_derived]
impl Decay {
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
    fn __odyn_parameter_jacobian(
        &self,
        t: f64,
        __odyn_y: f64,
        __odyn_z: f64,
        __odyn_dfdp: &mut ::odyn::__private::nalgebra::DMatrix<f64>,
    ) {
        let __odyn_time: f64 = t;
        let mut __odyn_s0: usize = usize::MAX;
        if self.c > 0.0 {
            __odyn_s0 = 0usize;
        } else {
            __odyn_s0 = 1usize;
        }
        let __odyn_p3: f64 = self.c;
        let __odyn_e9: f64 = __odyn_p3 * __odyn_time;
        let __odyn_e20: f64 = if __odyn_s0 == 0usize { __odyn_y } else { (0f64) };
        let __odyn_e21: f64 = -__odyn_e20;
        let __odyn_e22: f64 = if __odyn_s0 == 0usize { (0f64) } else { (1f64) };
        let __odyn_e23: f64 = -__odyn_e22;
        let __odyn_e24: f64 = __odyn_e21 + __odyn_e23;
        let __odyn_e25: f64 = ::odyn::math::Transcendental::cos(__odyn_e9);
        let __odyn_e26: f64 = __odyn_time * __odyn_e25;
        let __odyn_e27: f64 = __odyn_e20 + __odyn_e22;
        let __odyn_e28: f64 = __odyn_z * __odyn_z;
        let __odyn_e29: f64 = -__odyn_e28;
        if __odyn_dfdp.shape() != (2usize, 2usize) {
            *__odyn_dfdp = ::odyn::__private::nalgebra::DMatrix::zeros(2usize, 2usize);
        } else {
            __odyn_dfdp.fill(0.0);
        }
        __odyn_dfdp[(0usize, 0usize)] = __odyn_e24;
        __odyn_dfdp[(0usize, 1usize)] = __odyn_e26;
        __odyn_dfdp[(1usize, 0usize)] = __odyn_e27;
        __odyn_dfdp[(1usize, 1usize)] = __odyn_e29;
    }
}
///The `#[param]` parameters of [`Decay`] as one value (`Parameters::parameter_values`), generated by `#[system]`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DecayParameters {
    ///`Decay::k`.
    pub k: f64,
    ///`Decay::c`.
    pub c: f64,
}
#[automatically_derived]
impl ::odyn::Parameters for Decay {
    type Values = DecayParameters;
    const NAMES: &'static [&'static str] = &["k", "c"];
    fn parameter_values(&self) -> DecayParameters {
        DecayParameters {
            k: self.k,
            c: self.c,
        }
    }
    fn set_parameter_values(&mut self, values: DecayParameters) {
        self.k = values.k;
        self.c = values.c;
    }
    fn parameters(&self) -> ::std::vec::Vec<f64> {
        ::std::vec![self.k, self.c]
    }
    fn write_parameters(&mut self, values: &[f64]) {
        self.k = values[0usize];
        self.c = values[1usize];
    }
    ///∂f/∂p for the parameters k, c: 4 structural non-zeros, derived by `#[system]` from the model's code.
    fn parameter_jacobian(
        &self,
        t: f64,
        y: &DecayState,
        dfdp: &mut ::odyn::__private::nalgebra::DMatrix<f64>,
    ) {
        self.__odyn_parameter_jacobian(t, y.y, y.z, dfdp)
    }
}
