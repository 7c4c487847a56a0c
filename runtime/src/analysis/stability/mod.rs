//! Where each method stops being stable: predicted from the spectrum of the generated Jacobian
//! ([`predicted_limit`]; for field models, whose Jacobians are too big for dense eigenvalues,
//! from Gershgorin's discs, [`gershgorin_limit`]), and measured by bisection on long runs.
//!
//! A limit is a step dt: `0.0` means no dt is stable (explicit Euler on an undamped oscillator)
//! and `f64::INFINITY` means every dt is (implicit Euler on a dissipative or conservative linear
//! model).

use crate::Simulate;
use crate::{Error, Method, Model, Result, State};
mod predicted;

pub use predicted::{
    disc_limit, eigenvalues, gershgorin_limit, predicted_limit, stability_polynomial,
};

/// How a measured limit is found. [`measured_limit`] checks every field first.
#[derive(Clone, Debug, PartialEq)]
pub struct StabilityProbe {
    /// Steps per trial run, at least 2 (default 20 000).
    pub steps: u64,
    /// A run is unstable when the largest energy of its second half exceeds that of its first
    /// half by more than this fraction, finite and non-negative (default 1e-3), or when it
    /// diverges. Bounded methods
    /// oscillate within a fixed band, so both halves see the same maximum; an unstable one grows.
    pub growth: f64,
    /// Bisection stops when the bracket is this narrow relative to its lower end, from 1e-15
    /// (about the resolution of `f64`) to 1 (default 1e-6).
    pub precision: f64,
    /// The scan from below raises dt by this ratio a trial, from 1.001 to 2 (default 1.01): a
    /// band of unstable dt narrower than this ratio may be stepped over.
    pub scan_ratio: f64,
}

impl StabilityProbe {
    /// Checks every setting.
    ///
    /// Errors: [`Error::InvalidInput`] naming the first setting out of its documented range.
    pub fn check(&self) -> Result<()> {
        if self.steps < 2 {
            return Err(Error::invalid(
                "StabilityProbe::steps",
                format!("must be at least 2, got {}", self.steps),
            ));
        }
        if !(self.growth.is_finite() && self.growth >= 0.0) {
            return Err(Error::invalid(
                "StabilityProbe::growth",
                format!("must be finite and non-negative, got {:?}", self.growth),
            ));
        }
        if !(1e-15..=1.0).contains(&self.precision) {
            return Err(Error::invalid(
                "StabilityProbe::precision",
                format!("must be from 1e-15 to 1, got {:?}", self.precision),
            ));
        }
        if !(1.001..=2.0).contains(&self.scan_ratio) {
            return Err(Error::invalid(
                "StabilityProbe::scan_ratio",
                format!("must be from 1.001 to 2, got {:?}", self.scan_ratio),
            ));
        }
        Ok(())
    }
}

impl Default for StabilityProbe {
    fn default() -> Self {
        StabilityProbe {
            steps: 20_000,
            growth: 1e-3,
            precision: 1e-6,
            scan_ratio: 1.01,
        }
    }
}

/// The range of dt the search covers: far beyond any step a run takes either way, with room
/// for the products of dt with the model's rates (ω²dt² stays finite for |ω| < 10¹⁰⁰).
const SMALLEST_DT: f64 = 1e-150;
const LARGEST_DT: f64 = 1e150;

/// The largest dt at which `method` keeps `model` bounded from `state`: the first instability,
/// met scanning dt upwards.
///
/// The energy is the model's own when it defines one, else the squared norm of the state.
///
/// The search, whatever the `guess` (it only sets where the search starts):
///
/// 1. **bracket**: from the guess, dt is multiplied (or divided) by 2, 4, 16, 256, … — the
///    factor squares each trial, so any dt from 10⁻¹⁵⁰ to 10¹⁵⁰ is reached in about 10 trials —
///    until stability changes; a method stable at 10¹⁵⁰ is stable everywhere (∞), one unstable
///    at 10⁻¹⁵⁰ nowhere (0);
/// 2. the bracket is halved geometrically until its ends are within a factor 2;
/// 3. **scan from below**: from half the stable end, dt rises by `probe.scan_ratio` a trial to
///    the first unstable dt, so a method whose stable set has gaps (the sixth-order
///    compositions, stable again past their first limit) reports its first edge;
/// 4. bisection between the last stable and the first unstable dt to `probe.precision`.
///
/// An unstable band below half the stable end the bracket found, or narrower than
/// `probe.scan_ratio`, is not seen.
///
/// Errors: [`Error::InvalidInput`] for a guess that is not finite and positive or a `probe`
/// setting out of range (see [`StabilityProbe::check`]); the run's own input errors.
pub fn measured_limit<M: Model>(
    model: &M,
    state: &M::State,
    method: Method,
    guess: f64,
    probe: &StabilityProbe,
) -> Result<f64> {
    if !(guess.is_finite() && guess > 0.0) {
        return Err(Error::invalid(
            "guess",
            format!("must be finite and positive, got {guess}"),
        ));
    }
    probe.check()?;
    let stable = |dt: f64| bounded(model, state, method, dt, probe);
    let largest = LARGEST_DT;
    let guess = guess.clamp(SMALLEST_DT, largest);
    // 1. Bracket: lo stable, hi unstable.
    let (mut lo, mut hi) = if stable(guess)? {
        let (mut lo, mut factor) = (guess, 2.0f64);
        loop {
            if lo >= largest {
                return Ok(f64::INFINITY);
            }
            let next = (lo * factor).min(largest);
            if !stable(next)? {
                break (lo, next);
            }
            (lo, factor) = (next, factor * factor);
        }
    } else {
        let (mut hi, mut factor) = (guess, 2.0f64);
        loop {
            if hi <= SMALLEST_DT {
                return Ok(0.0);
            }
            let next = (hi / factor).max(SMALLEST_DT);
            if stable(next)? {
                break (next, hi);
            }
            (hi, factor) = (next, factor * factor);
        }
    };
    // 2. To within a factor 2, halving the bracket's logarithm.
    while hi > 2.0 * lo {
        let mid = lo.sqrt() * hi.sqrt();
        if stable(mid)? { lo = mid } else { hi = mid }
    }
    // 3. Scan from below, from a stable start.
    let mut from = 0.5 * lo;
    while !stable(from)? {
        if from <= SMALLEST_DT {
            return Ok(0.0);
        }
        (hi, from) = (from, 0.5 * from);
    }
    let (mut lo, mut hi) = loop {
        let next = from * probe.scan_ratio;
        if next >= hi {
            break (from, hi);
        }
        if !stable(next)? {
            break (from, next);
        }
        from = next;
    };
    // 4. Bisection. precision ≥ 1e-15 ends this within ~50 halvings; the cap guards against a
    // bracket the relative test cannot shrink.
    for _ in 0..200 {
        if hi - lo <= probe.precision * lo {
            break;
        }
        let mid = 0.5 * (lo + hi);
        if stable(mid)? { lo = mid } else { hi = mid }
    }
    Ok(lo)
}

/// One trial: does `method` at `dt` stay bounded over `probe.steps` steps?
fn bounded<M: Model>(
    model: &M,
    state: &M::State,
    method: Method,
    dt: f64,
    probe: &StabilityProbe,
) -> Result<bool> {
    let run = model
        .simulate()
        .initial_state(state.clone())
        .integrator(method)
        .dt(dt)
        .steps(probe.steps)
        .run_partial();
    let (trajectory, failure) = run?;
    match failure {
        Some(Error::Diverged { .. } | Error::NewtonDidNotConverge { .. }) => return Ok(false),
        Some(other) => return Err(other),
        None => {}
    }
    let energy = |s: &crate::Sample<M::State>| {
        s.energy
            .unwrap_or_else(|| s.state.as_slice().iter().map(|x| x * x).sum())
    };
    let half = trajectory.samples.len() / 2;
    let peak = |samples: &[crate::Sample<M::State>]| samples.iter().map(energy).fold(0.0, f64::max);
    let (first, second) = (
        peak(&trajectory.samples[..=half]),
        peak(&trajectory.samples[half..]),
    );
    Ok(second.is_finite() && second <= first * (1.0 + probe.growth))
}
