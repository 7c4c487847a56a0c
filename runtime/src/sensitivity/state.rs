//! [`SensitivityState`]: a model's state followed by its sensitivities, column by column.

use std::sync::Arc;

use nalgebra::{DMatrix, DMatrixView};

use crate::State;

/// The state of a [`super::Sensitive`] model: the n components of the model's state y, then one
/// column of n components per sensitivity (each parameter's ∂y/∂pⱼ, then ∂y/∂y₀ᵢ if asked),
/// laid out column by column.
#[derive(Clone, Debug, PartialEq)]
pub struct SensitivityState {
    values: Vec<f64>,
    n: usize,
    names: Arc<Names>,
}

/// The component names of the state and of the columns.
#[derive(Debug, PartialEq)]
struct Names {
    state: Vec<String>,
    columns: Vec<String>,
}

impl SensitivityState {
    /// `y` with zero sensitivities in the named columns.
    pub(super) fn new<S: State>(y: &S, columns: Vec<String>) -> Self {
        let n = y.as_slice().len();
        let mut values = vec![0.0; n * (1 + columns.len())];
        values[..n].copy_from_slice(y.as_slice());
        SensitivityState {
            values,
            n,
            names: Arc::new(Names {
                state: (0..n).map(|i| y.component_name(i)).collect(),
                columns,
            }),
        }
    }

    /// The model's state components y.
    pub fn state(&self) -> &[f64] {
        &self.values[..self.n]
    }

    /// The sensitivities as an n × m matrix: entry (i, j) is ∂yᵢ/∂(column j), the columns in the
    /// order of [`SensitivityState::columns`].
    pub fn sensitivities(&self) -> DMatrixView<'_, f64> {
        let n = self.n;
        DMatrixView::from_slice(&self.values[n..], n, self.names.columns.len())
    }

    /// The sensitivities, owned.
    pub fn sensitivity_matrix(&self) -> DMatrix<f64> {
        self.sensitivities().into_owned()
    }

    /// The names of the sensitivities' columns: the parameters, then `y(t0)` per component when
    /// the initial state is included.
    pub fn columns(&self) -> &[String] {
        &self.names.columns
    }
}

impl State for SensitivityState {
    fn as_slice(&self) -> &[f64] {
        &self.values
    }

    fn as_mut_slice(&mut self) -> &mut [f64] {
        &mut self.values
    }

    /// `x` for the state, `dx/dk` for a sensitivity.
    fn component_name(&self, index: usize) -> String {
        let n = self.n;
        if index < n {
            return self.names.state[index].clone();
        }
        let (column, row) = ((index - n) / n, (index - n) % n);
        format!("d{}/d{}", self.names.state[row], self.names.columns[column])
    }
}
