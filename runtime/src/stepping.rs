//! [`Stepping`]: how a run sizes its steps, the one description a run's options, its
//! [`Trajectory`](crate::Trajectory) and a work-precision [`Measurement`](crate::work_precision::Measurement)
//! share.

use crate::control::Tolerances;

/// How the steps are sized.
#[derive(Clone, Debug, PartialEq)]
pub enum Stepping {
    /// Every step is dt (the methods with an error estimate run this way too, for order tests).
    Fixed(f64),
    /// Each step as large as the tolerances allow (methods with an error estimate only).
    Adaptive(Tolerances),
}

impl Stepping {
    /// The fixed step, for a fixed-step run.
    pub fn dt(&self) -> Option<f64> {
        match self {
            Stepping::Fixed(dt) => Some(*dt),
            Stepping::Adaptive(_) => None,
        }
    }

    /// The tolerances, for an adaptive run.
    pub fn tolerances(&self) -> Option<&Tolerances> {
        match self {
            Stepping::Fixed(_) => None,
            Stepping::Adaptive(tolerances) => Some(tolerances),
        }
    }

    /// The relative tolerance, for an adaptive run.
    pub fn rtol(&self) -> Option<f64> {
        self.tolerances().map(|t| t.rtol)
    }
}
