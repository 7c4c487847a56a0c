//! The generated state types: layout, zero-copy views, arithmetic, names.

use crate::common;

use common::{KeplerState, LorenzState, PairState, SpringState};
use odyn::prelude::*;

#[test]
fn layout_is_positions_then_velocities() {
    // Pair declares a, b, va, vb: the state lays out a, b[0], b[1], va, vb[0], vb[1].
    let s = PairState {
        a: 1.0,
        b: [2.0, 3.0],
        va: 4.0,
        vb: [5.0, 6.0],
    };
    assert_eq!(s.as_slice(), &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    assert_eq!(PairState::LEN, 6);
    let names: Vec<_> = (0..6).map(|i| s.component_name(i)).collect();
    assert_eq!(names, ["a", "b[0]", "b[1]", "va", "vb[0]", "vb[1]"]);
    assert_eq!(s.component_name(6), "#6");
}

#[test]
fn the_vector_view_is_zero_copy_and_round_trips() {
    let mut s = KeplerState {
        r: Vector2::new(1.0, 2.0),
        v: Vector2::new(3.0, 4.0),
    };
    let view = s.as_vector();
    assert_eq!(view.as_ptr(), (&s as *const KeplerState).cast::<f64>());
    assert_eq!(*view, SVector::<f64, 4>::new(1.0, 2.0, 3.0, 4.0));
    s.as_vector_mut()[3] = 9.0;
    assert_eq!(s.v.y, 9.0);
    let back = KeplerState::from(SVector::<f64, 4>::from(s));
    assert_eq!(back, s);
    assert_eq!(KeplerState::zeros().as_slice(), &[0.0; 4]);
}

#[test]
fn arithmetic_is_componentwise() {
    let a = LorenzState {
        x: 1.0,
        y: 2.0,
        z: 3.0,
    };
    let b = LorenzState {
        x: 0.5,
        y: -1.0,
        z: 2.0,
    };
    assert_eq!(
        a + b,
        LorenzState {
            x: 1.5,
            y: 1.0,
            z: 5.0
        }
    );
    assert_eq!(
        a - b,
        LorenzState {
            x: 0.5,
            y: 3.0,
            z: 1.0
        }
    );
    assert_eq!(2.0 * a, a * 2.0);
    assert_eq!(
        -a,
        LorenzState {
            x: -1.0,
            y: -2.0,
            z: -3.0
        }
    );
    let mut c = a;
    c += b;
    c -= b;
    assert_eq!(c, a);
    let s = SpringState { x: 1.0, v: 2.0 };
    assert_eq!(std::mem::size_of_val(&s), 16);
}

#[test]
fn the_user_functions_stay_callable_on_the_struct() {
    let spring = common::Spring {
        x: 2.0,
        v: 1.0,
        k: 3.0,
        b: 0.5,
        m: 1.0,
    };
    // The original methods read the struct's own fields.
    assert_eq!(spring.energy(), 0.5 + 6.0);
    assert_eq!(spring.acceleration(), -6.5);
    // The trait evaluates at any state.
    let mut a = SpringState::zeros();
    SecondOrder::acceleration(&spring, 0.0, &SpringState { x: 1.0, v: 0.0 }, &mut a);
    assert_eq!(a.v, -3.0);
    assert_eq!(
        Model::energy(&spring, &SpringState { x: 0.0, v: 2.0 }),
        Some(2.0)
    );
}
