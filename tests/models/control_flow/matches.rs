//! `match` and `if let` on the state, read as the `if` chain they mean (`lower/matches.rs`).

use crate::common::{Rng, check};
use odyn::prelude::*;

/// `match` and `if let` on the state: the lowering reads them as the `if` chain they mean
/// (`lower/matches.rs`). Ranges, an or-pattern, a constant, a guard of comparisons and a binding
/// as a value; a `match` as a statement changing a local; an `if let` with a range; a
/// parameter's `match` with a guard on the state; a `return` from a `match` among the
/// function's statements.
#[system]
#[derive(Clone, Copy, Debug)]
struct Zones {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    k: f64,
}

/// A constant in a pattern: compared with, not bound.
const EDGE: f64 = 2.5;

#[system]
impl Zones {
    fn acceleration(&self) -> f64 {
        let spring = match self.x {
            ..-1.0 => -self.k * (self.x + 1.0) - 1.0,
            -1.0..0.0 | 0.5..=1.0 => -self.x,
            EDGE => 0.0,
            d if d > 2.0 && self.v < 0.0 => -d * d,
            _ => 0.1 * self.x,
        };
        let mut drag = 0.0;
        match self.v * self.x {
            p @ 1.0.. => drag = -0.3 * p,
            ..=-1.0 => drag = 0.2 * self.v,
            _ => {}
        }
        if let ..0.0 = self.v - 1.5 {
            drag += 0.05 * self.v * self.v;
        } else {
            drag -= 0.01 * self.x;
        }
        // A parameter's `match` with a guard on the state.
        let boost = match self.k as u32 {
            50 if self.v > 0.5 => 0.1 * self.v,
            _ => 0.0,
        };
        match self.x {
            far if far >= 3.5 => return -far * self.v,
            _ => {}
        }
        spring + drag + boost
    }
}

/// [`Zones`] written with `if`s, the same arithmetic.
#[system]
#[derive(Clone, Copy, Debug)]
struct ZonesByIf {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    k: f64,
}

#[system]
impl ZonesByIf {
    fn acceleration(&self) -> f64 {
        let spring = if self.x < -1.0 {
            -self.k * (self.x + 1.0) - 1.0
        } else if (self.x >= -1.0 && self.x < 0.0) || (self.x >= 0.5 && self.x <= 1.0) {
            -self.x
        } else if self.x == EDGE {
            0.0
        } else if self.x > 2.0 && self.v < 0.0 {
            -self.x * self.x
        } else {
            0.1 * self.x
        };
        let mut drag = 0.0;
        let p = self.v * self.x;
        if p >= 1.0 {
            drag = -0.3 * p;
        } else if p <= -1.0 {
            drag = 0.2 * self.v;
        }
        if self.v - 1.5 < 0.0 {
            drag += 0.05 * self.v * self.v;
        } else {
            drag -= 0.01 * self.x;
        }
        let boost = if self.k as u32 == 50 && self.v > 0.5 {
            0.1 * self.v
        } else {
            0.0
        };
        if self.x >= 3.5 {
            return -self.x * self.v;
        }
        spring + drag + boost
    }
}

#[test]
fn matches_on_the_state_are_differentiated_arm_by_arm() {
    let model = Zones {
        x: 0.0,
        v: 0.0,
        k: 50.0,
    };
    let by_if = ZonesByIf {
        x: 0.0,
        v: 0.0,
        k: 50.0,
    };
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    let mut states = Vec::new();
    for _ in 0..400 {
        let y = ZonesState {
            x: rng.uniform(-2.0, 4.0),
            v: rng.uniform(-2.0, 3.0),
        };
        states.push(y);
    }
    // On the switching surfaces too: the arm Rust's comparison takes, in both forms.
    for x in [-1.0, 0.0, 0.5, 1.0, EDGE, 3.5] {
        for v in [-1.0, 0.0, 0.5, 1.5, 2.0] {
            states.push(ZonesState { x, v });
        }
    }
    for y in states {
        let other = ZonesByIfState { x: y.x, v: y.v };
        let (mut a, mut b) = (y, y);
        model.derivative(0.0, &y, &mut a);
        let mut b_if = other;
        by_if.derivative(0.0, &other, &mut b_if);
        b.v = b_if.v;
        assert_eq!(a.v.to_bits(), b.v.to_bits(), "f at {y:?}");
        let mut j = model.jacobian_matrix(&y);
        model.jacobian(0.0, &y, &mut j);
        let mut j_if = by_if.jacobian_matrix(&other);
        by_if.jacobian(0.0, &other, &mut j_if);
        assert_eq!(j, j_if, "∂f/∂y at {y:?}");
    }
    // At x = EDGE exactly the constant's arm is taken (∂a/∂x = 0; drag and boost vanish at
    // v = 0); a hair away, the last arm's 0.1.
    for (x, expected) in [(EDGE, 0.0), (EDGE + 1e-9, 0.1)] {
        let y = ZonesState { x, v: 0.0 };
        let mut j = model.jacobian_matrix(&y);
        model.jacobian(0.0, &y, &mut j);
        assert_eq!(odyn::DenseMatrix::entry(&j, 1, 0), expected, "x = {x}");
    }
    // Against central differences away from the switching surfaces (x = −1, 0, ½, 1, 2, 2.5,
    // 3.5; v = 0, ½, 1.5; v·x = ±1).
    let away = |r: &mut Rng| loop {
        let (x, v) = (r.uniform(-2.0, 4.0), r.uniform(-2.0, 3.0));
        let near = |value: f64, surfaces: &[f64]| surfaces.iter().any(|s| (value - s).abs() < 0.05);
        if !near(x, &[-1.0, 0.0, 0.5, 1.0, 2.0, EDGE, 3.5])
            && !near(v, &[0.0, 0.5, 1.5])
            && !near(v * x, &[-1.0, 1.0])
        {
            return ZonesState { x, v };
        }
    };
    check(&model, 0.0, 200, away);
}
