//! Coefficients of the Runge–Kutta and Rosenbrock methods, one file per method, each citing the
//! paper and code its numbers come from (checked independently by `scripts/check_tableaux.py`).

pub(super) mod dop853;
pub(super) mod rodas5p;
pub(super) mod tsit5;
