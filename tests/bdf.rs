//! BDF (`Method::Bdf`): its order at a fixed order, accuracy on stiff problems, step counts
//! against SciPy's `BDF` (the algorithm it implements), Jacobian and factorization reuse,
//! stability, events and save times.

mod common;

#[path = "../examples/common/stiff_models.rs"]
mod stiff_models;

use common::{Robertson, VanDerPol};
use odyn::prelude::*;

#[test]
fn explore() {
    let rober = Robertson {
        a: 1.0,
        b: 0.0,
        c: 0.0,
    };
    let run = rober
        .simulate()
        .integrator(Method::Bdf)
        .tolerances(1e-6, 1e-12)
        .duration(1e5)
        .dense_output(false)
        .run()
        .unwrap();
    let s = run.last().state;
    let r = stiff_models::ROBERTSON_1E5;
    eprintln!(
        "robertson {} : {:?} err {:e}",
        run.stats,
        run.stats,
        ((s.a - r[0]) / r[0])
            .abs()
            .max(((s.b - r[1]) / r[1]).abs())
            .max(((s.c - r[2]) / r[2]).abs())
    );
    let hires = stiff_models::Hires {
        y: [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0057],
    };
    let run = hires
        .simulate()
        .integrator(Method::Bdf)
        .tolerances(1e-6, 1e-10)
        .duration(321.8122)
        .dense_output(false)
        .run()
        .unwrap();
    eprintln!("hires {:?}", run.stats);
    let vdp = VanDerPol {
        y1: 2.0,
        y2: 0.0,
        mu: 1000.0,
    };
    let run = vdp
        .simulate()
        .integrator(Method::Bdf)
        .tolerances(1e-6, 1e-9)
        .duration(2000.0)
        .dense_output(false)
        .run()
        .unwrap();
    eprintln!("vdp {:?} {:?}", run.stats, run.last().state);
}
