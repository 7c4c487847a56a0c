//! `Trajectory::sample_at`: an exact time wins, a near one is matched within the spacing of the
//! samples, never by a tolerance that reaches a neighbour. The fourth hardening probe found
//! `sample_at(1e-10)` returning the sample at 5e-10, `sample_at(0.0)` not the initial sample,
//! and `sample_at(f64::INFINITY)` returning Ok.

use odyn::prelude::*;

use crate::parameters::Decay;

#[test]
fn samples_are_found_at_their_own_times_however_close() {
    let decay = Decay { c: 1.0, k: 1e9 };
    let times: Vec<f64> = (1..=10).map(|i| i as f64 * 1e-10).collect();
    let run = decay
        .simulate()
        .integrator(Method::Dop853)
        .duration(1e-9)
        .save_at(&times)
        .run()
        .unwrap();
    for &t in &times {
        assert_eq!(run.sample_at(t).unwrap().t, t);
    }
    let initial = run.sample_at(0.0).unwrap();
    assert_eq!((initial.t, initial.step, initial.state.c), (0.0, 0, 1.0));
    // Halfway between two samples is no sample (the old tolerance, 1e-9·max(1, |t|), matched
    // anything within 1e-9).
    assert!(run.sample_at(1.5e-10).is_err());
    for t in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
        assert!(
            matches!(run.sample_at(t), Err(Error::InvalidInput { .. })),
            "{t}"
        );
    }
}

#[test]
fn a_time_computed_differently_still_finds_its_sample() {
    let decay = Decay { c: 1.0, k: 0.5 };
    let run = decay
        .simulate()
        .integrator(Method::Tsit5)
        .duration(1.0)
        .save_at(&[0.3, 0.6])
        .run()
        .unwrap();
    // 0.1·3 = 0.30000000000000004 and 0.2·3 = 0.6000000000000001: a float spacing away.
    assert_eq!(run.sample_at(0.1 * 3.0).unwrap().t, 0.3);
    assert_eq!(run.sample_at(0.2 * 3.0).unwrap().t, 0.6);
    assert!(run.sample_at(0.3 + 1e-6).is_err());
}
