//! Forward sensitivities: s = ∂y/∂p for the `#[param]` parameters of a model (and, if asked,
//! ∂y/∂y₀), integrated with the solution as the augmented system
//!
//! y′ = f(t, y),   sⱼ′ = ∂f/∂y · sⱼ + ∂f/∂pⱼ,   sⱼ(t₀) = 0   (and sᵢ′ = ∂f/∂y · sᵢ, sᵢ(t₀) = eᵢ
//! for ∂y/∂y₀ᵢ),
//!
//! the "simultaneous" forward method (Hairer, Nørsett & Wanner, *Solving ODEs I*, §I.14; SUNDIALS
//! CVODES, `CV_SIMULTANEOUS`). ∂f/∂y and ∂f/∂p are the ones `#[system]` generated, exact. The
//! augmented system is an ordinary model, [`Sensitive`], so every method runs it: RK4 at a
//! fixed step, Tsit5 and DOP853 adaptively with dense output, `save_at` and events, and for stiff
//! models Rodas5P, Rosenbrock23, BDF and implicit Euler on the augmented Jacobian (`jacobian.rs`:
//! block lower-triangular with J on its diagonal). Its error control includes the
//! sensitivities, as CVODES does by default (`errconS`); [`crate::fit`] holds ∂y/∂pⱼ to
//! atol/|pⱼ|, CVODES's scaling.
//!
//! A differential–algebraic model (M·y′ = f) has M·sⱼ′ = ∂f/∂y·sⱼ + ∂f/∂pⱼ: the augmented
//! system is a DAE with the mass matrix diag(M, …, M), run by the methods that take one, and
//! its algebraic sensitivities are made consistent (`algebraic.rs`) wherever the algebraic
//! components are (IDAS's `IDACalcIC` does the same for its sensitivities).

mod algebraic;
mod events;
mod jacobian;
mod state;

use std::cell::{Cell, RefCell};

pub use jacobian::{AugmentedFactors, AugmentedJacobian};
pub use state::SensitivityState;

use nalgebra::DMatrix;

use crate::model::Unavailable;
use crate::{DenseMatrix, Jacobian, Method, Model, Parameters, State, Tolerances};

/// What a [`Sensitive`] model evaluates into, allocated once: the state, f, J and ∂f/∂p, and a
/// second J and ∂f/∂p for the augmented Jacobian's differences.
#[derive(Debug)]
struct Scratch<M: Jacobian> {
    y: M::State,
    f: M::State,
    jacobian: M::Matrix,
    dfdp: DMatrix<f64>,
    jacobian_minus: M::Matrix,
    dfdp_minus: DMatrix<f64>,
}

/// A model together with its forward sensitivities, as one model whose state is a
/// [`SensitivityState`]: `Sensitive::new(&model).simulate()…run()` integrates both.
#[derive(Debug)]
pub struct Sensitive<'m, M: Parameters + Jacobian> {
    model: &'m M,
    initial_state: bool,
    scratch: RefCell<Scratch<M>>,
    template: SensitivityState,
    work: Cell<SensitivityWork>,
}

pub use crate::stats::SensitivityWork;

impl<'m, M> Sensitive<'m, M>
where
    M: Parameters + Jacobian,
    M::Matrix: DenseMatrix,
{
    /// Sensitivities with respect to the model's `#[param]` parameters, from the model's own
    /// state.
    pub fn new(model: &'m M) -> Self {
        Self::build(model, false)
    }

    /// Sensitivities with respect to the parameters and to every component of the initial
    /// state (∂y/∂y₀, the columns after the parameters' ones).
    pub fn with_initial_state(model: &'m M) -> Self {
        Self::build(model, true)
    }

    fn build(model: &'m M, initial_state: bool) -> Self {
        let y = model.state();
        let n = y.as_slice().len();
        let mut columns: Vec<String> = M::NAMES.iter().map(|p| (*p).to_string()).collect();
        if initial_state {
            columns.extend((0..n).map(|i| format!("{}(t0)", y.component_name(i))));
        }
        let template = SensitivityState::new(&y, columns);
        let scratch = Scratch {
            jacobian: model.jacobian_matrix(&y),
            jacobian_minus: model.jacobian_matrix(&y),
            f: y.clone(),
            dfdp: DMatrix::zeros(n, M::NAMES.len()),
            dfdp_minus: DMatrix::zeros(n, M::NAMES.len()),
            y,
        };
        Sensitive {
            model,
            initial_state,
            scratch: RefCell::new(scratch),
            template,
            work: Cell::new(SensitivityWork::default()),
        }
    }

    /// Tolerances for the augmented state: `atol` on the model's components and on ∂y/∂y₀, and
    /// atol/|pⱼ| on ∂y/∂pⱼ (CVODES's scaling with p̄ = p: an error of atol in pⱼ·∂y/∂pⱼ, the
    /// change of y over a relative change of pⱼ, weighs as atol does in y; atol itself for
    /// pⱼ = 0). With `sensitivities_in_error_test` false the sensitivities are left out of the
    /// error test (atol +∞, [`crate::Atol::PerComponent`]): steps are sized for y alone, as
    /// CVODES's `errconS = false`; the sensitivities are then only as accurate as those steps
    /// make them.
    pub fn tolerances(
        &self,
        rtol: f64,
        atol: f64,
        sensitivities_in_error_test: bool,
    ) -> Tolerances {
        let n = self.model.state().as_slice().len();
        let columns = self.template.columns().len();
        let parameters = self.model.parameters();
        let mut atols = vec![atol; n];
        for c in 0..columns {
            let scale = match parameters.get(c) {
                Some(&p) if p != 0.0 && p.is_finite() => p.abs(),
                _ => 1.0,
            };
            let value = if sensitivities_in_error_test {
                atol / scale
            } else {
                f64::INFINITY
            };
            atols.extend(std::iter::repeat_n(value, n));
        }
        Tolerances::per_component(rtol, atols)
    }

    /// The model's evaluations so far, all runs of this `Sensitive` together.
    pub fn work(&self) -> SensitivityWork {
        self.work.get()
    }

    /// Adds to [`Sensitive::work`].
    fn count(&self, derivatives: u64, jacobians: u64, parameter_jacobians: u64) {
        let mut work = self.work.get();
        work.derivatives += derivatives;
        work.jacobians += jacobians;
        work.parameter_jacobians += parameter_jacobians;
        self.work.set(work);
    }
}

impl<M> crate::model::Sealed for Sensitive<'_, M>
where
    M: Parameters + Jacobian,
    M::Matrix: DenseMatrix,
{
}

impl<M> Model for Sensitive<'_, M>
where
    M: Parameters + Jacobian,
    M::Matrix: DenseMatrix,
{
    fn sensitivity_work(&self) -> SensitivityWork {
        self.work.get()
    }

    type State = SensitivityState;
    type SecondOrder = Unavailable<Self>;
    type Jacobian = Self;
    const NAME: &'static str = M::NAME;
    const DEFAULT_METHOD: Method = Method::Dop853;
    const DEFAULT_DT: Option<f64> = M::DEFAULT_DT;
    const DEFAULT_RTOL: Option<f64> = M::DEFAULT_RTOL;
    const DEFAULT_ATOL: Option<f64> = M::DEFAULT_ATOL;
    /// A differential–algebraic model's sensitivities solve M·sⱼ′ = J·sⱼ + ∂f/∂pⱼ: the
    /// augmented system has the mass matrix diag(M, …, M) ([`Sensitive::mass`](Model::mass)).
    const MASS_MATRIX: bool = M::MASS_MATRIX;

    /// diag(M, …, M): the model's M once for the state and once per sensitivity column, the
    /// state's block first (what [`AugmentedJacobian`]'s factorization reads).
    fn mass(&self, state: &SensitivityState) -> crate::Result<crate::Mass> {
        let y = self.model.state();
        let own = self.model.mass(&y)?;
        let n = y.as_slice().len();
        let blocks = state.as_slice().len() / n.max(1);
        let entries = (0..blocks)
            .flat_map(|b| {
                own.entries()
                    .iter()
                    .map(move |&(i, j, m)| (b * n + i, b * n + j, m))
            })
            .collect();
        Ok(crate::Mass::from_entries(blocks * n, entries))
    }

    /// The model's algebraic components made consistent ([`crate::consistent`]), then their
    /// sensitivities: the algebraic equations differentiated, ∂g/∂y·s + ∂g/∂z·s_z + ∂g/∂pⱼ = 0,
    /// solved for s_z in every column.
    fn consistent(
        &self,
        t: f64,
        z: &mut SensitivityState,
        newton: &crate::NewtonOptions,
    ) -> crate::Result<()> {
        if M::ALGEBRAIC.is_empty() {
            return Ok(());
        }
        let scratch = &mut *self.scratch.borrow_mut();
        let n = scratch.y.as_slice().len();
        scratch.y.as_mut_slice().copy_from_slice(&z.as_slice()[..n]);
        self.model.consistent(t, &mut scratch.y, newton)?;
        z.as_mut_slice()[..n].copy_from_slice(scratch.y.as_slice());
        self.model.jacobian(t, &scratch.y, &mut scratch.jacobian);
        self.model
            .parameter_jacobian(t, &scratch.y, &mut scratch.dfdp);
        self.count(0, 1, 1);
        algebraic::consistent_sensitivities::<M>(
            &scratch.jacobian,
            &scratch.dfdp,
            z.as_mut_slice(),
            n,
            t,
            &scratch.y,
        )
    }

    /// The model's state, the parameters' sensitivities zero and ∂y/∂y₀ the identity.
    fn state(&self) -> SensitivityState {
        let mut s = self.template.clone();
        let y = self.model.state();
        let n = y.as_slice().len();
        let values = s.as_mut_slice();
        values[..n].copy_from_slice(y.as_slice());
        if self.initial_state {
            let first = n * (1 + M::NAMES.len());
            for i in 0..n {
                values[first + i * n + i] = 1.0;
            }
        }
        s
    }

    fn derivative(&self, t: f64, y: &SensitivityState, dydt: &mut SensitivityState) {
        let scratch = &mut *self.scratch.borrow_mut();
        let values = y.as_slice();
        let n = scratch.y.as_slice().len();
        scratch.y.as_mut_slice().copy_from_slice(&values[..n]);
        self.model.derivative(t, &scratch.y, &mut scratch.f);
        self.model.jacobian(t, &scratch.y, &mut scratch.jacobian);
        self.model
            .parameter_jacobian(t, &scratch.y, &mut scratch.dfdp);
        self.count(1, 1, 1);
        let out = dydt.as_mut_slice();
        out[..n].copy_from_slice(scratch.f.as_slice());
        let parameters = M::NAMES.len();
        let columns = (values.len() - n) / n;
        for c in 0..columns {
            let s = &values[n * (1 + c)..n * (2 + c)];
            let ds = &mut out[n * (1 + c)..n * (2 + c)];
            for (i, d) in ds.iter_mut().enumerate() {
                let mut sum = if c < parameters {
                    scratch.dfdp[(i, c)]
                } else {
                    0.0
                };
                for (k, sk) in s.iter().enumerate() {
                    sum += scratch.jacobian.entry(i, k) * sk;
                }
                *d = sum;
            }
        }
    }

    fn energy(&self, _: &SensitivityState) -> Option<f64> {
        None
    }

    /// The sensitivities' jump at the change ([`events`](self) module docs).
    fn complete_change(
        &self,
        t: f64,
        before: &SensitivityState,
        after: &mut SensitivityState,
        jump: crate::drive::Jump<'_, SensitivityState>,
    ) -> crate::Result<()> {
        self.jump(t, before, after, jump)
    }

    fn as_second_order(&self) -> Option<&Unavailable<Self>> {
        None
    }

    fn as_jacobian(&self) -> Option<&Self> {
        Some(self)
    }
}
