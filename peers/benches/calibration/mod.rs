//! The rule both equal-accuracy benches calibrate by: for a target error, the loosest tolerance
//! of a sweep whose error is at or below it.

/// What a sweep offers for one target.
pub enum Pick {
    /// No tolerance of the sweep met the target; the smallest error it reached.
    NotReached(f64),
    /// The index of the loosest tolerance that met it, and a note on the tighter ones: a pick
    /// whose tighter neighbours miss the target met it by luck (error cancellation) — kept, as
    /// the rule says, but flagged.
    Met(usize, String),
}

/// Applies the rule to `errors` (one per tolerance, loosest first).
pub fn pick(errors: &[f64], target: f64) -> Pick {
    let Some(k) = errors.iter().position(|&e| e <= target) else {
        return Pick::NotReached(errors.iter().copied().fold(f64::INFINITY, f64::min));
    };
    let misses = errors[k..].iter().filter(|&&e| e > target).count();
    let note = if misses == 0 {
        "all meet the target".to_string()
    } else {
        format!("{misses} of {} miss it", errors.len() - k - 1)
    };
    Pick::Met(k, note)
}
