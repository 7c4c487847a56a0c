//! DOP853 against a reference implementation of the same method: SciPy's `DOP853`, a port of
//! Hairer's code. Configured as SciPy configures it — integral control with exponent 1/8,
//! safety 0.9, factors in [0.2, 10], SciPy's first step — odyn's Dop853 must take the same steps
//! on the Arenstorf orbit and the Lorenz system. The figures are SciPy 1.17.1's, printed by
//! `scripts/scipy_dop853_steps.py` (accepted and rejected attempts counted by instrumenting the
//! solver); the final errors against the references of `scripts/reference_adaptive.py`.

use crate::common;

use common::{Arenstorf, Lorenz};
use odyn::prelude::*;
use odyn::{AdaptiveOptions, Controller};

/// One row of the script's table: tolerance (rtol = atol), SciPy's first step h₀, accepted and
/// rejected attempts.
struct Row {
    tol: f64,
    h0: f64,
    accepted: u64,
    rejected: u64,
}

const ARENSTORF: [Row; 3] = [
    Row {
        tol: 1e-6,
        h0: 2.638_485_616_063_170_4e-3,
        accepted: 66,
        rejected: 23,
    },
    Row {
        tol: 1e-9,
        h0: 2.638_485_616_063_169_5e-3,
        accepted: 136,
        rejected: 50,
    },
    Row {
        tol: 1e-12,
        h0: 2.638_485_616_063_17e-3,
        accepted: 298,
        rejected: 59,
    },
];

const LORENZ: [Row; 3] = [
    Row {
        tol: 1e-6,
        h0: 1.757_906_384_836_574_8e-2,
        accepted: 239,
        rejected: 74,
    },
    Row {
        tol: 1e-9,
        h0: 1.757_906_384_836_574_8e-2,
        accepted: 550,
        rejected: 107,
    },
    Row {
        tol: 1e-12,
        h0: 9.116_678_588_366_295e-3,
        accepted: 1277,
        rejected: 46,
    },
];

fn scipy_control(h0: f64) -> AdaptiveOptions {
    AdaptiveOptions {
        dt_initial: Some(h0),
        controller: Some(Controller::scipy(7)),
        ..AdaptiveOptions::default()
    }
}

/// The same accepted and rejected counts as SciPy's DOP853 on the periodic Arenstorf orbit, to
/// the step (measured: 66/23, 136/50, 298/59 for both). The two codes form the stage sums in
/// different orders, so their states differ in the last bits; a decision right at a tolerance
/// boundary could flip, but none does here. The final error against the 30-digit reference y(T)
/// of `scripts/reference_adaptive.py` is SciPy's too (6.9e-3, 7.3e-6, 1.3e-9; SciPy 6.9e-3,
/// 7.3e-6, 1.5e-9).
#[test]
fn arenstorf_steps_match_scipy() {
    let model = Arenstorf::orbit();
    // y(fl(T)) in f64 arithmetic of the data, Taylor series at 50 digits.
    let reference = [
        9.939_999_999_999_088e-1,
        -3.030_943_022_982_418_5e-13,
        -4.928_536_581_055_052_6e-11,
        -2.001_585_106_393_27,
    ];
    for row in &ARENSTORF {
        let run = model
            .simulate()
            .tolerances(row.tol, row.tol)
            .adaptive(scipy_control(row.h0))
            .duration(Arenstorf::PERIOD)
            .record_every(u64::MAX)
            .run_with::<odyn::method::Dop853>()
            .unwrap();
        let s = run.last().state;
        let error = common::max_abs_difference(&[s.y1, s.y2, s.v1, s.v2], &reference);
        let stats = run.stats;
        eprintln!(
            "Arenstorf tol {:e}: odyn {} accepted / {} rejected (SciPy {} / {}), error {error:.2e}",
            row.tol, stats.steps, stats.rejected, row.accepted, row.rejected
        );
        assert_eq!((stats.steps, stats.rejected), (row.accepted, row.rejected));
        assert!(error < 1e4 * row.tol, "{error}");
    }
}

/// The same on Lorenz to t = 20 from (1, 0, 0), to the step (239/74, 550/107, 1277/46), although
/// the flow is chaotic and amplifies last-bit differences by ~e^{0.9t}.
#[test]
fn lorenz_steps_match_scipy() {
    let model = Lorenz {
        x: 1.0,
        y: 0.0,
        z: 0.0,
        ..Lorenz::classic()
    };
    for row in &LORENZ {
        let run = model
            .simulate()
            .integrator(Method::Dop853)
            .tolerances(row.tol, row.tol)
            .adaptive(scipy_control(row.h0))
            .duration(20.0)
            .record_every(u64::MAX)
            .run()
            .unwrap();
        let stats = run.stats;
        eprintln!(
            "Lorenz tol {:e}: odyn {} accepted / {} rejected (SciPy {} / {})",
            row.tol, stats.steps, stats.rejected, row.accepted, row.rejected
        );
        assert_eq!((stats.steps, stats.rejected), (row.accepted, row.rejected));
    }
}
