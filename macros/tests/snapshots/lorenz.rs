impl Lorenz {
    fn derivative(&self) -> LorenzState {
        LorenzState {
            x: self.sigma * (self.y - self.x),
            y: self.x * (self.rho - self.z) - self.y,
            z: self.x * self.y - self.beta * self.z,
        }
    }
}
#[automatically_derived]
impl Lorenz {
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
        _: f64,
        __odyn_x: f64,
        __odyn_y: f64,
        __odyn_z: f64,
    ) -> LorenzState {
        LorenzState {
            x: self.sigma * (__odyn_y - __odyn_x),
            y: __odyn_x * (self.rho - __odyn_z) - __odyn_y,
            z: __odyn_x * __odyn_y - self.beta * __odyn_z,
        }
    }
}
#[automatically_derived]
impl ::odyn::Model for Lorenz {
    type State = LorenzState;
    type SecondOrder = ::odyn::__private::Unavailable<Self>;
    const NAME: &'static str = "Lorenz";
    const DEFAULT_METHOD: ::odyn::Method = ::odyn::Method::Rk4;
    const DEFAULT_DT: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_RTOL: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_ATOL: ::core::option::Option<f64> = ::core::option::Option::None;
    #[inline]
    fn state(&self) -> LorenzState {
        LorenzState {
            x: self.x,
            y: self.y,
            z: self.z,
        }
    }
    #[inline(always)]
    fn derivative(&self, t: f64, y: &LorenzState, dydt: &mut LorenzState) {
        *dydt = self.__odyn_derivative(t, y.x, y.y, y.z);
    }
    #[inline]
    fn energy(&self, state: &LorenzState) -> ::core::option::Option<f64> {
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
impl ::odyn::__private::Sealed for Lorenz {}
const _: () = {
    let _ = <Lorenz as ::odyn::Model>::DEFAULT_DT;
    let _ = <Lorenz as ::odyn::Model>::DEFAULT_RTOL;
    let _ = <Lorenz as ::odyn::Model>::DEFAULT_ATOL;
};
const _: () = {
    let _ = <Lorenz>::derivative;
};
#[automatically_derived]
impl Lorenz {
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
        __odyn_y: f64,
        __odyn_z: f64,
        __odyn_jac: &mut ::odyn::__private::nalgebra::SMatrix<f64, 3, 3>,
    ) {
        let __odyn_p0: f64 = self.sigma;
        let __odyn_p1: f64 = self.rho;
        let __odyn_p2: f64 = self.beta;
        let __odyn_e3: f64 = -__odyn_x;
        let __odyn_e8: f64 = -__odyn_z;
        let __odyn_e9: f64 = __odyn_p1 + __odyn_e8;
        let __odyn_e21: f64 = -__odyn_p0;
        let __odyn_e22: f64 = -__odyn_p2;
        *__odyn_jac = ::odyn::__private::nalgebra::SMatrix::from_array_storage(
            ::odyn::__private::nalgebra::ArrayStorage([
                [__odyn_e21, __odyn_e9, __odyn_y],
                [__odyn_p0, (-1f64), __odyn_x],
                [0.0f64, __odyn_e3, __odyn_e22],
            ]),
        );
    }
}
#[automatically_derived]
impl ::odyn::Jacobian for Lorenz {
    type Matrix = ::odyn::__private::nalgebra::SMatrix<f64, 3, 3>;
    ///The 8 structural non-zeros of ∂f/∂y, derived by `#[system]` from the model's code.
    const NONZEROS: &'static [(usize, usize)] = &[
        (0usize, 0usize),
        (0usize, 1usize),
        (1usize, 0usize),
        (1usize, 1usize),
        (1usize, 2usize),
        (2usize, 0usize),
        (2usize, 1usize),
        (2usize, 2usize),
    ];
    #[inline]
    fn jacobian_matrix(
        &self,
        _: &LorenzState,
    ) -> ::odyn::__private::nalgebra::SMatrix<f64, 3, 3> {
        ::odyn::__private::nalgebra::SMatrix::<f64, 3, 3>::zeros()
    }
    #[inline]
    fn jacobian(
        &self,
        t: f64,
        y: &LorenzState,
        jacobian: &mut ::odyn::__private::nalgebra::SMatrix<f64, 3, 3>,
    ) {
        self.__odyn_jacobian(t, y.x, y.y, y.z, jacobian)
    }
    /// The model's function does not read the time: ∂f/∂t = 0.
    const TIME_DEPENDENT: bool = false;
    #[inline]
    fn time_derivative(&self, _: f64, _: &LorenzState, dfdt: &mut LorenzState) {
        ::odyn::State::as_mut_slice(dfdt).fill(0.0);
    }
}
