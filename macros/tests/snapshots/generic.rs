impl<const N: usize> Chain<N> {
    fn acceleration(&self) -> [f64; N] {
        let mut a = [0.0; N];
        for i in 1..N {
            a[i] = -self.k * (self.x[i] - self.x[i - 1]);
        }
        a
    }
}
#[automatically_derived]
impl<const N: usize> Chain<N> {
    #[doc(hidden)]
    #[inline]
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
        __odyn_x: &[f64; N],
        __odyn_v: &[f64; N],
    ) -> [f64; N] {
        let mut a = [0.0; N];
        for i in 1..N {
            a[i] = -self.k * ((*__odyn_x)[i] - (*__odyn_x)[i - 1]);
        }
        a
    }
}
#[automatically_derived]
impl<const N: usize> ::odyn::Model for Chain<N> {
    type State = ChainState<N>;
    type SecondOrder = Self;
    const NAME: &'static str = "Chain";
    const DEFAULT_METHOD: ::odyn::Method = ::odyn::Method::Rk4;
    const DEFAULT_DT: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_RTOL: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_ATOL: ::core::option::Option<f64> = ::core::option::Option::None;
    #[inline]
    fn state(&self) -> ChainState<N> {
        ChainState { x: self.x, v: self.v }
    }
    #[inline(always)]
    fn derivative(&self, t: f64, y: &ChainState<N>, dydt: &mut ChainState<N>) {
        <Self as ::odyn::SecondOrder>::acceleration(self, t, y, dydt);
        dydt.x = y.v;
    }
    #[inline]
    fn energy(&self, state: &ChainState<N>) -> ::core::option::Option<f64> {
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
impl<const N: usize> ::odyn::__private::Sealed for Chain<N> {}
#[automatically_derived]
impl<const N: usize> ::odyn::SecondOrder for Chain<N> {
    const READS_VELOCITY: bool = false;
    #[inline(always)]
    fn acceleration(&self, t: f64, y: &ChainState<N>, accel: &mut ChainState<N>) {
        let a = self.__odyn_acceleration(t, &y.x, &y.v);
        accel.v = a;
    }
}
#[automatically_derived]
impl<const N: usize> Chain<N> {
    #[allow(dead_code)]
    fn __odyn_used() {
        let _ = Self::acceleration;
    }
}
#[automatically_derived]
impl<const N: usize> ::odyn::Jacobian for Chain<N> {
    type Matrix = ::odyn::FaerDense;
    /// Not known: the Jacobian is taken by finite differences.
    const NONZEROS: &'static [(usize, usize)] = &[];
    /// False: a const-generic model's Jacobian is central differences of f.
    const EXACT: bool = false;
    #[inline]
    fn jacobian_matrix(&self, state: &ChainState<N>) -> ::odyn::FaerDense {
        ::odyn::FaerDense::zeros(::odyn::State::as_slice(state).len())
    }
    #[inline]
    fn jacobian(&self, t: f64, y: &ChainState<N>, jacobian: &mut ::odyn::FaerDense) {
        ::odyn::__private::central_differences(
            self,
            t,
            y,
            |row, column, value| jacobian.set(row, column, value),
        )
    }
    /// The model's function does not read the time: ∂f/∂t = 0.
    const TIME_DEPENDENT: bool = false;
    #[inline]
    fn time_derivative(&self, _: f64, _: &ChainState<N>, dfdt: &mut ChainState<N>) {
        ::odyn::State::as_mut_slice(dfdt).fill(0.0);
    }
}
