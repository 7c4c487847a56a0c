impl Heat {
    fn conduction(&self, u: Stencil) -> f64 {
        self.d * u.laplacian() / (self.dx * self.dx)
    }
}
#[automatically_derived]
impl Heat {
    #[doc(hidden)]
    #[inline(always)]
    #[allow(
        unused_variables,
        unused_assignments,
        unused_mut,
        unused_parens,
        non_snake_case,
        clippy::all
    )]
    fn __odyn_conduction_jacobian(&self, u: Stencil) -> [f64; 5] {
        let __odyn_p0: f64 = self.d;
        let __odyn_p1: f64 = self.dx;
        let __odyn_p2: f64 = self.dx;
        let __odyn_e20: f64 = __odyn_p1 * __odyn_p2;
        let __odyn_e25: f64 = __odyn_p0 * (-4f64);
        let __odyn_e26: f64 = __odyn_e25 / __odyn_e20;
        let __odyn_e27: f64 = __odyn_p0 / __odyn_e20;
        [__odyn_e26, __odyn_e27, __odyn_e27, __odyn_e27, __odyn_e27]
    }
}
#[automatically_derived]
impl ::odyn::grid::GridSystem<1> for Heat {
    const FIELDS: [&'static str; 1] = ["u"];
    const BLOCKS: &'static [::odyn::grid::Block] = &[
        ::odyn::grid::Block {
            row: 0,
            column: 0,
            neighbour: 0,
        },
        ::odyn::grid::Block {
            row: 0,
            column: 0,
            neighbour: 1,
        },
        ::odyn::grid::Block {
            row: 0,
            column: 0,
            neighbour: 2,
        },
        ::odyn::grid::Block {
            row: 0,
            column: 0,
            neighbour: 3,
        },
        ::odyn::grid::Block {
            row: 0,
            column: 0,
            neighbour: 4,
        },
    ];
    #[inline(always)]
    fn grids(&self) -> [&::odyn::grid::Grid; 1] {
        [&self.u]
    }
    #[inline(always)]
    #[allow(unused_variables)]
    fn cell(
        &self,
        stencils: &[::odyn::grid::Stencil; 1],
        at: ::odyn::grid::Place,
    ) -> [f64; 1] {
        [self.conduction(stencils[0])]
    }
    #[inline(always)]
    #[allow(unused_variables)]
    fn cell_jacobian(
        &self,
        stencils: &[::odyn::grid::Stencil; 1],
        at: ::odyn::grid::Place,
        blocks: &mut [f64],
    ) {
        blocks.copy_from_slice(&self.__odyn_conduction_jacobian(stencils[0]));
    }
    #[inline(always)]
    #[allow(unused_variables)]
    fn cell_time_derivative(
        &self,
        stencils: &[::odyn::grid::Stencil; 1],
        at: ::odyn::grid::Place,
    ) -> [f64; 1] {
        [0.0; 1]
    }
}
#[automatically_derived]
impl ::odyn::Jacobian for Heat {
    type Matrix = ::odyn::grid::GridJacobian;
    /// Empty: a field model's pattern comes from its grid at run time.
    const NONZEROS: &'static [(usize, usize)] = &[];
    fn jacobian_matrix(&self, state: &HeatState) -> Self::Matrix {
        ::odyn::__private::grid::jacobian_matrix(self, state)
    }
    #[inline]
    fn jacobian(&self, t: f64, y: &HeatState, jacobian: &mut Self::Matrix) {
        ::odyn::__private::grid::jacobian(self, t, y, jacobian)
    }
    /// A cell's rate does not read the time: ∂f/∂t = 0.
    const TIME_DEPENDENT: bool = false;
    #[inline]
    fn time_derivative(&self, _: f64, _: &HeatState, dfdt: &mut HeatState) {
        ::odyn::State::as_mut_slice(dfdt).fill(0.0);
    }
}
#[automatically_derived]
impl ::odyn::Model for Heat {
    type State = HeatState;
    type SecondOrder = ::odyn::__private::Unavailable<Self>;
    const NAME: &'static str = "Heat";
    const DEFAULT_METHOD: ::odyn::Method = ::odyn::Method::ImplicitEuler;
    const DEFAULT_DT: ::core::option::Option<f64> = ::core::option::Option::Some({
        let value = (0.001) as f64;
        ::core::assert!(
            value.is_finite() && value > 0.0,
            "`dt` in `#[system]` must be finite and positive"
        );
        value
    });
    const DEFAULT_RTOL: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_ATOL: ::core::option::Option<f64> = ::core::option::Option::None;
    fn state(&self) -> HeatState {
        ::odyn::__private::grid::state(&[&self.u], &["u"])
    }
    #[inline]
    fn derivative(&self, t: f64, y: &HeatState, dydt: &mut HeatState) {
        ::odyn::__private::grid::derivative(self, t, y, dydt)
    }
    fn energy(&self, _: &HeatState) -> ::core::option::Option<f64> {
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
    fn check(&self, state: &HeatState) -> ::odyn::Result<()> {
        ::odyn::__private::grid::check(self, state)?;
        ::core::result::Result::Ok(())
    }
}
#[automatically_derived]
impl ::odyn::__private::Sealed for Heat {}
const _: () = {
    let _ = <Heat as ::odyn::Model>::DEFAULT_DT;
    let _ = <Heat as ::odyn::Model>::DEFAULT_RTOL;
    let _ = <Heat as ::odyn::Model>::DEFAULT_ATOL;
};
