//! [`GridState`]: a field model's state, every field's values one after another.

use std::fmt;

use super::Grid;
use crate::{Error, Result, State};

/// The state of a field model: every field's values, one field after another.
#[derive(PartialEq)]
pub struct GridState {
    pub(super) values: Vec<f64>,
    pub(super) nx: usize,
    pub(super) ny: usize,
    pub(super) names: &'static [&'static str],
}

impl GridState {
    /// The state of a model's grids (their sizes checked by [`Model::check`](crate::Model::check)).
    pub(crate) fn from_grids(grids: &[&Grid], names: &'static [&'static str]) -> Self {
        let (nx, ny) = grids.first().map_or((0, 0), |g| (g.nx, g.ny));
        GridState {
            values: grids
                .iter()
                .flat_map(|g| g.values.iter().copied())
                .collect(),
            nx,
            ny,
            names,
        }
    }

    /// Cells along x.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Cells along y.
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Number of fields.
    pub fn fields(&self) -> usize {
        self.names.len()
    }

    /// The values of field `k` (declaration order), k = j·nx + i; empty past the last field.
    pub fn field(&self, k: usize) -> &[f64] {
        let n = self.nx * self.ny;
        self.values.get(k * n..(k + 1) * n).unwrap_or(&[])
    }

    /// The values of field `k`, mutably; empty past the last field.
    pub fn field_mut(&mut self, k: usize) -> &mut [f64] {
        let n = self.nx * self.ny;
        self.values.get_mut(k * n..(k + 1) * n).unwrap_or(&mut [])
    }

    /// The values of the field called `name`, if there is one.
    pub fn by_name(&self, name: &str) -> Option<&[f64]> {
        let k = self.names.iter().position(|n| *n == name)?;
        Some(self.field(k))
    }
}

impl fmt::Debug for GridState {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("GridState")
            .field("nx", &self.nx)
            .field("ny", &self.ny)
            .field("fields", &self.names)
            .finish_non_exhaustive()
    }
}

impl State for GridState {
    #[inline(always)]
    fn as_slice(&self) -> &[f64] {
        &self.values
    }

    #[inline(always)]
    fn as_mut_slice(&mut self) -> &mut [f64] {
        &mut self.values
    }

    fn component_name(&self, index: usize) -> String {
        let n = (self.nx * self.ny).max(1);
        let name = self.names.get(index / n).copied().unwrap_or("?");
        let k = index % n;
        format!("{name}[{},{}]", k % self.nx.max(1), k / self.nx.max(1))
    }

    /// A copy whose values are reserved with `try_reserve_exact`.
    ///
    /// Errors: [`Error::InvalidInput`] (field `grid`) giving the grid's size when the copy cannot
    /// be allocated.
    fn try_clone(&self) -> Result<Self> {
        let mut values = Vec::new();
        if values.try_reserve_exact(self.values.len()).is_err() {
            let fields = self.names.len();
            let what = format!(
                "is {}×{} with {fields} field{}",
                self.nx,
                self.ny,
                if fields == 1 { "" } else { "s" }
            );
            return Err(Error::copy_refused(
                "grid",
                what,
                self.values.len(),
                "a coarser grid",
            ));
        }
        values.extend_from_slice(&self.values);
        Ok(GridState { values, ..*self })
    }
}

impl Clone for GridState {
    fn clone(&self) -> Self {
        GridState {
            values: self.values.clone(),
            ..*self
        }
    }

    /// Reuses the buffer: the integrators copy states every step and must not allocate.
    fn clone_from(&mut self, source: &Self) {
        self.values.clone_from(&source.values);
        (self.nx, self.ny, self.names) = (source.nx, source.ny, source.names);
    }
}
