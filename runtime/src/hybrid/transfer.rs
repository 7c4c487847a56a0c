//! How velocity goes from the grid back to the particles: APIC, or a PIC/FLIP blend.

use crate::{Error, Result};

/// The grid-to-particle velocity transfer.
///
/// | transfer | keeps | loses |
/// |---|---|---|
/// | APIC (Jiang et al. 2015) | linear and angular momentum, exactly | little: the affine part of the flow survives |
/// | PIC (`Blend { flip: 0.0 }`) | linear momentum | angular momentum and energy, fast (a rotating body spins down) |
/// | FLIP (`Blend { flip: 1.0 }`) | detail | stability: noise grows where particles outnumber nodes |
///
/// APIC carries each particle's affine velocity C (its velocity gradient) into the grid as
/// m·C·(xᵢ − xₚ) and back as C = 4/h²·Σᵢ wᵢₚ·vᵢ·(xᵢ − xₚ)ᵀ (quadratic B-splines). A blend
/// (Zhu & Bridson 2005) sets vₚ ← flip·(vₚ + Σᵢ wᵢₚ·Δvᵢ) + (1 − flip)·Σᵢ wᵢₚ·vᵢ, Δvᵢ the grid's
/// change over the step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Transfer {
    /// Affine particle-in-cell (the default).
    #[default]
    Apic,
    /// PIC/FLIP blend, `flip` in [0, 1]: 0 is PIC, 1 is pure FLIP (0.95–0.99 is usual for
    /// liquids). MPM takes only `flip: 0.0`: its transfer folds the stress into the grid's
    /// momentum (MLS-MPM), so the grid has no velocity before the forces to difference.
    Blend {
        /// The FLIP fraction.
        flip: f64,
    },
}

impl Transfer {
    /// PIC: `Blend { flip: 0.0 }`.
    pub const PIC: Transfer = Transfer::Blend { flip: 0.0 };

    /// The FLIP fraction of a blend, None for APIC.
    ///
    /// Errors: [`Error::InvalidInput`] for a fraction outside [0, 1] (NaN included).
    pub(crate) fn flip(&self) -> Result<Option<f64>> {
        match *self {
            Transfer::Apic => Ok(None),
            Transfer::Blend { flip } if (0.0..=1.0).contains(&flip) => Ok(Some(flip)),
            Transfer::Blend { flip } => Err(Error::invalid(
                "transfer",
                format!("the FLIP fraction must be in [0, 1], got {flip:?}"),
            )),
        }
    }
}
