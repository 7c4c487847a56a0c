//! What the linearly implicit methods share: J = ∂f/∂y and ∂f/∂t at the start of a step, and
//! the factorization of W = I − c·J (M − c·J for a model with a mass matrix M), each made once
//! and reused as long as it stays valid.

use crate::{Error, Jacobian, Mass, NewtonMatrix, Result, Stats};

/// J, ∂f/∂t and the factors of W for the current step.
///
/// Reuse: J and ∂f/∂t are evaluated at the first attempt from a state and kept while the driver
/// retries that state with smaller steps (a rejected step keeps (t, y)); W is refactorized only
/// when its c = γ·h changes, so a retried step costs one factorization and no Jacobian. Both are
/// dropped when a step is accepted or an event changes the state.
pub struct Linearization<M: Jacobian> {
    pub(super) jacobian: M::Matrix,
    factors: <M::Matrix as NewtonMatrix>::Factors,
    /// ∂f/∂t at the start of the step (zero for autonomous models, never evaluated).
    pub(super) dfdt: M::State,
    /// Whether `jacobian` and `dfdt` hold the current state's.
    current: bool,
    /// The c of the current factorization, if it is valid.
    factored: Option<f64>,
    /// M, for a model with a mass matrix ([`crate::Model::MASS_MATRIX`]); W = M − c·J then.
    pub(super) mass: Option<Mass>,
}

impl<M: Jacobian> Linearization<M> {
    /// Errors: [`Error::InvalidInput`] when ∂f/∂t's state cannot be allocated
    /// ([`crate::State::try_clone`]); [`Error::BadModel`] from [`crate::Model::mass`].
    pub(super) fn new(model: &M, y0: &M::State) -> Result<Self> {
        let jacobian = model.jacobian_matrix(y0);
        let mut dfdt = crate::State::try_clone(y0)?;
        crate::State::as_mut_slice(&mut dfdt).fill(0.0);
        let mass = crate::model::mass_of(model, y0)?;
        Ok(Linearization {
            factors: jacobian.factors(),
            jacobian,
            dfdt,
            current: false,
            factored: None,
            mass,
        })
    }

    /// `b += scale·M·x` (`b += scale·x` for an ODE).
    #[inline(always)]
    pub(super) fn mass_add(&self, b: &mut [f64], scale: f64, x: &[f64]) {
        match &self.mass {
            Some(mass) if M::MASS_MATRIX => mass.apply_add(scale, x, b),
            _ => super::axpy(b, scale, x),
        }
    }

    /// Evaluates J and ∂f/∂t at (t, y) unless they are already the current state's.
    ///
    /// Errors: [`Error::NonFiniteJacobian`] when J has a NaN or infinite entry.
    pub(super) fn evaluate(
        &mut self,
        model: &M,
        t: f64,
        y: &M::State,
        stats: &mut Stats,
    ) -> Result<()> {
        if self.current {
            return Ok(());
        }
        model.jacobian(t, y, &mut self.jacobian);
        stats.jacobian_evaluations += 1;
        finite_jacobian(&self.jacobian, t, y)?;
        if M::TIME_DEPENDENT {
            model.time_derivative(t, y, &mut self.dfdt);
            stats.time_derivative_evaluations += 1;
        }
        self.current = true;
        self.factored = None;
        Ok(())
    }

    /// Factorizes W = I − c·J (M − c·J) unless it already is, for this c.
    ///
    /// Errors: [`Error::SingularMatrix`] (retriable: the driver tries a smaller step).
    pub(super) fn factorize(&mut self, c: f64, t: f64, h: f64, stats: &mut Stats) -> Result<()> {
        if self.factored == Some(c) {
            return Ok(());
        }
        self.factored = None;
        stats.factorizations += 1;
        let factored = match &self.mass {
            Some(mass) if M::MASS_MATRIX => {
                self.jacobian
                    .factorize_mass(c, mass.entries(), &mut self.factors)
            }
            _ => self.jacobian.factorize(c, &mut self.factors),
        };
        factored.map_err(|_| Error::SingularMatrix { t, dt: h })?;
        self.factored = Some(c);
        Ok(())
    }

    /// Solves W·x = b in place.
    ///
    /// Errors: [`Error::SingularMatrix`] when x is not finite.
    pub(super) fn solve(&mut self, b: &mut [f64], t: f64, h: f64, stats: &mut Stats) -> Result<()> {
        stats.linear_solves += 1;
        self.jacobian
            .solve(&mut self.factors, b)
            .map_err(|_| Error::SingularMatrix { t, dt: h })
    }

    /// The step was accepted or the state changed: the next step linearizes afresh.
    pub(super) fn invalidate(&mut self) {
        self.current = false;
        self.factored = None;
    }
}

/// Ok when every entry of J, as last evaluated at (t, y), is finite.
///
/// Errors: [`Error::NonFiniteJacobian`] naming the first entry that is not.
#[inline]
pub(crate) fn finite_jacobian<S: crate::State>(
    jacobian: &impl NewtonMatrix,
    t: f64,
    y: &S,
) -> Result<()> {
    match jacobian.non_finite_entry() {
        None => Ok(()),
        Some((row, column, value)) => Err(Error::NonFiniteJacobian {
            t,
            row: y.component_name(row),
            column: y.component_name(column),
            value,
        }),
    }
}

impl<M: Jacobian> Clone for Linearization<M> {
    fn clone(&self) -> Self {
        Linearization {
            jacobian: self.jacobian.clone(),
            factors: self.factors.clone(),
            dfdt: self.dfdt.clone(),
            current: self.current,
            factored: self.factored,
            mass: self.mass.clone(),
        }
    }
}
