//! Searches on one step's dense output: where a condition crosses zero, and whether a state
//! that left an event's surface comes back to it.

use super::Direction;
use crate::drive::ulp;

/// Where a latched event stands after a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Rearm {
    /// g reached the side it came from at this point (t, g): a crossing after it counts.
    Armed((f64, f64)),
    /// g is still on its way back to the surface: no crossing in this step.
    Held,
    /// g moved away from the surface on the far side: the change did not reverse the crossing.
    Released,
    /// g turned back towards the surface and away again without reaching it, at this time: a
    /// return sooner than the tolerance resolves.
    Unresolved(f64),
}

/// Where the event latched on the `side` it came from stands after the step from `start` to
/// `end` (each (t, g)): the highest point of side·g on the step, by golden-section search to
/// within `tolerance` in t (Kiefer, Proc. AMS 4 (1953) 502), says whether the state came back;
/// `back` says whether it leaves the surface towards that side, for a hop too short to find.
pub(super) fn rearm(
    mut g: impl FnMut(f64) -> f64,
    side: f64,
    back: bool,
    start: (f64, f64),
    end: (f64, f64),
    tolerance: f64,
) -> Rearm {
    let phi = |g: f64| side * g;
    let (a, b) = (start.0, end.0);
    let mut best = if phi(end.1) >= phi(start.1) {
        end
    } else {
        start
    };
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let (mut lo, mut hi) = (a, b);
    let mut x1 = hi - ratio * (hi - lo);
    let mut x2 = lo + ratio * (hi - lo);
    let (mut f1, mut f2) = (g(x1), g(x2));
    for _ in 0..200 {
        for (x, f) in [(x1, f1), (x2, f2)] {
            if phi(f) > phi(best.1) {
                best = (x, f);
            }
        }
        if phi(best.1) > 0.0 || hi - lo <= tolerance.max(4.0 * ulp(hi)) {
            break;
        }
        if phi(f1) >= phi(f2) {
            (hi, x2, f2) = (x2, x1, f1);
            x1 = hi - ratio * (hi - lo);
            f1 = g(x1);
        } else {
            (lo, x1, f1) = (x1, x2, f2);
            x2 = lo + ratio * (hi - lo);
            f2 = g(x2);
        }
    }
    if phi(best.1) > 0.0 {
        Rearm::Armed(best)
    } else if best.0 == b {
        Rearm::Held
    } else if best.0 == a && !back {
        Rearm::Released
    } else {
        Rearm::Unresolved(best.0)
    }
}

/// Whether g going from `g0` to `g1` crosses zero in `direction`. A g that reaches zero exactly
/// at the end counts; one that leaves zero at the start does not (it crossed in the last step).
pub(super) fn crosses(g0: f64, g1: f64, direction: Direction) -> bool {
    let rising = g0 < 0.0 && g1 >= 0.0;
    let falling = g0 > 0.0 && g1 <= 0.0;
    match direction {
        Direction::Rising => rising,
        Direction::Falling => falling,
        Direction::Either => rising || falling,
    }
}

/// The zero of g in [a, b], where g(a) and g(b) have opposite signs (or g(b) = 0), to within
/// `tolerance` in t: the Illinois variant of regula falsi (Dowell & Jarratt, BIT 11 (1971)
/// 168), superlinear, with bisection steps if it stalls. Returns the end of the final bracket
/// on the far side of the root, so the located event never precedes the crossing.
pub(super) fn locate(
    mut g: impl FnMut(f64) -> f64,
    (mut a, mut ga): (f64, f64),
    (mut b, mut gb): (f64, f64),
    tolerance: f64,
) -> f64 {
    if gb == 0.0 {
        return b;
    }
    let mut side = 0i8;
    for iteration in 0..200 {
        if (b - a).abs() <= tolerance {
            break;
        }
        // Every third step bisects: Illinois alone can crawl on a flat g, and 66 halvings in
        // the 200 iterations reach any tolerance.
        let mut t = if iteration % 3 == 2 {
            0.5 * (a + b)
        } else {
            (a * gb - b * ga) / (gb - ga)
        };
        if !(t > a.min(b) && t < a.max(b)) {
            t = 0.5 * (a + b);
            if t == a || t == b {
                // Adjacent floats: the bracket cannot shrink further.
                break;
            }
        }
        let gt = g(t);
        if gt == 0.0 {
            return t;
        }
        if (gt > 0.0) == (gb > 0.0) {
            b = t;
            gb = gt;
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        } else {
            a = t;
            ga = gt;
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        }
    }
    b
}

#[cfg(test)]
mod tests {
    use super::{Direction, crosses, locate};

    #[test]
    fn crossings_respect_the_direction() {
        assert!(crosses(1.0, -1.0, Direction::Falling));
        assert!(!crosses(1.0, -1.0, Direction::Rising));
        assert!(crosses(-1.0, 0.0, Direction::Rising));
        assert!(!crosses(0.0, 1.0, Direction::Either));
        assert!(crosses(1.0, -1.0, Direction::Either));
    }

    #[test]
    fn roots_are_located_to_the_tolerance() {
        // cos t on [1, 2]: root π/2.
        let t = locate(f64::cos, (1.0, 1f64.cos()), (2.0, 2f64.cos()), 1e-14);
        assert!((t - std::f64::consts::FRAC_PI_2).abs() < 2e-14, "{t}");
        assert!(t >= std::f64::consts::FRAC_PI_2);
        // A very flat function still converges (bisection fallback).
        let g = |t: f64| (t - 0.3).powi(9);
        let t = locate(g, (0.0, g(0.0)), (1.0, g(1.0)), 1e-12);
        assert!((t - 0.3).abs() < 1e-11, "{t}");
    }
}
