//! The mass matrix M of a differential–algebraic model M·y′ = f(t, y): its non-zero entries,
//! applied to vectors and added into the matrices of the implicit methods.

use crate::{Error, Result, State};

/// A constant mass matrix, as its non-zero entries (row, column, value) in the state's layout.
///
/// [`crate::Model::mass`] builds it once per run: the identity with zeros at the algebraic
/// components (`#[algebraic]` fields), or the model's own `fn mass`. An ODE (M = I) never builds
/// one: the methods keep their identity form at no cost.
#[derive(Clone, Debug, PartialEq)]
pub struct Mass {
    dim: usize,
    entries: Vec<(usize, usize, f64)>,
}

impl Mass {
    /// The n×n identity with zero rows and columns at the `algebraic` components: a
    /// semi-explicit DAE, y′ = f(t, y, z), 0 = g(t, y, z).
    ///
    /// Errors: [`Error::BadModel`] naming `model` when an algebraic index is not below n.
    pub fn identity(model: &'static str, n: usize, algebraic: &[usize]) -> Result<Self> {
        if let Some(&i) = algebraic.iter().find(|&&i| i >= n) {
            return Err(Error::BadModel {
                model,
                what: format!("algebraic component {i}"),
                reason: format!("is beyond the state's {n} components"),
            });
        }
        let entries = (0..n)
            .filter(|i| !algebraic.contains(i))
            .map(|i| (i, i, 1.0))
            .collect();
        Ok(Mass { dim: n, entries })
    }

    /// The matrix `rows` (row-major, in the state's layout) of a model's `fn mass`, for states
    /// like `state`; zero entries are dropped.
    ///
    /// Errors: [`Error::BadModel`] naming `model` and the entry when `rows` is not as large as the
    /// state, an entry is not finite, or an entry in the row or column of an algebraic component
    /// is not zero (their equations are algebraic: M has nothing there).
    pub fn from_rows<S: State, const N: usize>(
        model: &'static str,
        rows: &[[f64; N]; N],
        algebraic: &[usize],
        state: &S,
    ) -> Result<Self> {
        let n = state.as_slice().len();
        let bad = |what: String, reason: String| Error::BadModel {
            model,
            what,
            reason,
        };
        if N != n {
            return Err(bad(
                "`fn mass`".into(),
                format!("returns a {N}×{N} matrix for a state of {n} components"),
            ));
        }
        let mut entries = Vec::new();
        for (i, row) in rows.iter().enumerate() {
            for (j, &value) in row.iter().enumerate() {
                let name = || {
                    format!(
                        "`fn mass` entry ({}, {})",
                        state.component_name(i),
                        state.component_name(j)
                    )
                };
                if !value.is_finite() {
                    return Err(bad(name(), format!("must be finite, got {value:?}")));
                }
                if value != 0.0 && (algebraic.contains(&i) || algebraic.contains(&j)) {
                    return Err(bad(
                        name(),
                        format!(
                            "is {value:e} in the row or column of an `#[algebraic]` component, \
                             where M is zero; make the component a `#[state]`, or the entry 0"
                        ),
                    ));
                }
                if value != 0.0 {
                    entries.push((i, j, value));
                }
            }
        }
        Ok(Mass { dim: n, entries })
    }

    /// The n×n matrix with the non-zero `entries` (row, column, value), each index below n: a
    /// block-diagonal mass matrix built from another's entries (forward sensitivities).
    pub fn from_entries(n: usize, entries: Vec<(usize, usize, f64)>) -> Self {
        debug_assert!(entries.iter().all(|&(i, j, _)| i < n && j < n));
        Mass { dim: n, entries }
    }

    /// The number of rows (= columns).
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The non-zero entries (row, column, value).
    pub fn entries(&self) -> &[(usize, usize, f64)] {
        &self.entries
    }

    /// Entry (row, column).
    pub fn entry(&self, row: usize, column: usize) -> f64 {
        self.entries
            .iter()
            .filter(|&&(i, j, _)| i == row && j == column)
            .map(|&(_, _, v)| v)
            .sum()
    }

    /// `out += scale·M·x`.
    #[inline]
    pub fn apply_add(&self, scale: f64, x: &[f64], out: &mut [f64]) {
        for &(i, j, m) in &self.entries {
            out[i] += scale * m * x[j];
        }
    }
}

/// The mass matrix of `model` for states like `y0`, checked, if the model has one
/// ([`crate::Model::MASS_MATRIX`]): what every method that takes it builds once per run.
///
/// Errors: [`Error::BadModel`] from [`crate::Model::mass`], or naming a row where M is zero and
/// f, by the Jacobian's structural pattern ([`crate::Jacobian::NONZEROS`]), reads no component:
/// the equation 0 = f(t) there determines nothing, and every M − c·J is singular.
pub(crate) fn mass_of<M: crate::Jacobian>(model: &M, y0: &M::State) -> Result<Option<Mass>> {
    if !M::MASS_MATRIX {
        return Ok(None);
    }
    let mass = model.mass(y0)?;
    if !M::NONZEROS.is_empty() {
        let empty = (0..mass.dim()).find(|&row| {
            mass.entries.iter().all(|e| e.0 != row) && M::NONZEROS.iter().all(|e| e.0 != row)
        });
        if let Some(row) = empty {
            return Err(Error::BadModel {
                model: M::NAME,
                what: format!("equation `{}`", y0.component_name(row)),
                reason: "has a zero row of the mass matrix and reads no component of the state: \
                         0 = f(t) there determines nothing, and M − c·J is singular at every \
                         step; give the row a rate (a non-zero M entry) or make it an algebraic \
                         equation that reads its component"
                    .into(),
            });
        }
    }
    Ok(Some(mass))
}
