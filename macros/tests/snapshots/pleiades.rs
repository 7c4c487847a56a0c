impl Pleiades {
    fn acceleration(&self) -> ([f64; 7], [f64; 7]) {
        let mut ax = [0.0; 7];
        let mut ay = [0.0; 7];
        for i in 0..7 {
            for j in (i + 1)..7 {
                let dx = self.x[j] - self.x[i];
                let dy = self.y[j] - self.y[i];
                let r2 = dx * dx + dy * dy;
                let w = 1.0 / (r2 * r2.sqrt());
                ax[i] += self.m[j] * w * dx;
                ay[i] += self.m[j] * w * dy;
                ax[j] -= self.m[i] * w * dx;
                ay[j] -= self.m[i] * w * dy;
            }
        }
        (ax, ay)
    }
}
#[automatically_derived]
impl Pleiades {
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
        __odyn_x: &[f64; 7],
        __odyn_y: &[f64; 7],
        __odyn_u: &[f64; 7],
        __odyn_v: &[f64; 7],
    ) -> ([f64; 7], [f64; 7]) {
        let mut ax = [0.0; 7];
        let mut ay = [0.0; 7];
        {
            {
                let i = 0;
                {
                    {
                        let j = [(i + 1), 7, 1][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 2][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 3][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 4][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 5][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 6][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                }
            }
            {
                let i = 1;
                {
                    {
                        let j = [(i + 1), 7, 2][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 3][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 4][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 5][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 6][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                }
            }
            {
                let i = 2;
                {
                    {
                        let j = [(i + 1), 7, 3][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 4][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 5][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 6][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                }
            }
            {
                let i = 3;
                {
                    {
                        let j = [(i + 1), 7, 4][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 5][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 6][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                }
            }
            {
                let i = 4;
                {
                    {
                        let j = [(i + 1), 7, 5][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                    {
                        let j = [(i + 1), 7, 6][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                }
            }
            {
                let i = 5;
                {
                    {
                        let j = [(i + 1), 7, 6][2];
                        let dx = (*__odyn_x)[j] - (*__odyn_x)[i];
                        let dy = (*__odyn_y)[j] - (*__odyn_y)[i];
                        let r2 = dx * dx + dy * dy;
                        let w = 1.0 / (r2 * r2.sqrt());
                        ax[i] += self.m[j] * w * dx;
                        ay[i] += self.m[j] * w * dy;
                        ax[j] -= self.m[i] * w * dx;
                        ay[j] -= self.m[i] * w * dy;
                    }
                }
            }
            {
                let i = 6;
                {}
            }
        }
        (ax, ay)
    }
}
#[automatically_derived]
impl ::odyn::Model for Pleiades {
    type State = PleiadesState;
    type SecondOrder = Self;
    const NAME: &'static str = "Pleiades";
    const DEFAULT_METHOD: ::odyn::Method = ::odyn::Method::Rk4;
    const DEFAULT_DT: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_RTOL: ::core::option::Option<f64> = ::core::option::Option::None;
    const DEFAULT_ATOL: ::core::option::Option<f64> = ::core::option::Option::None;
    #[inline]
    fn state(&self) -> PleiadesState {
        PleiadesState {
            x: self.x,
            y: self.y,
            u: self.u,
            v: self.v,
        }
    }
    #[inline(always)]
    fn derivative(&self, t: f64, y: &PleiadesState, dydt: &mut PleiadesState) {
        <Self as ::odyn::SecondOrder>::acceleration(self, t, y, dydt);
        dydt.x = y.u;
        dydt.y = y.v;
    }
    #[inline]
    fn energy(&self, state: &PleiadesState) -> ::core::option::Option<f64> {
        ::core::option::Option::None
    }
    #[inline(always)]
    fn as_second_order(&self) -> ::core::option::Option<&Self> {
        ::core::option::Option::Some(self)
    }
    type Jacobian = ::odyn::__private::Unavailable<Self>;
    #[inline(always)]
    fn as_jacobian(&self) -> ::core::option::Option<&Self::Jacobian> {
        ::core::option::Option::None
    }
}
#[automatically_derived]
impl ::odyn::__private::Sealed for Pleiades {}
const _: () = {
    let _ = <Pleiades as ::odyn::Model>::DEFAULT_DT;
    let _ = <Pleiades as ::odyn::Model>::DEFAULT_RTOL;
    let _ = <Pleiades as ::odyn::Model>::DEFAULT_ATOL;
};
#[automatically_derived]
impl ::odyn::SecondOrder for Pleiades {
    const READS_VELOCITY: bool = false;
    #[inline(always)]
    fn acceleration(&self, t: f64, y: &PleiadesState, accel: &mut PleiadesState) {
        let a = self.__odyn_acceleration(t, &y.x, &y.y, &y.u, &y.v);
        let (__odyn_a0, __odyn_a1) = a;
        accel.u = __odyn_a0;
        accel.v = __odyn_a1;
    }
}
const _: () = {
    let _ = <Pleiades>::acceleration;
};
