//! The fixed-step loop: the grid t₀ + n·dt, in blocks of bare steps between recorded samples,
//! with halving of failed implicit steps and events.

use super::*;

/// What the fixed-step loop needs of a driver: its track, a step of the method and a bare block
/// of them. Object-safe, so the loop (`run`, `advance_to`) is compiled once per model, not once
/// per (model, method); it calls the method through this at most once per grid step, or once per
/// block of [`BLOCK`] steps on the bare path.
pub(super) trait FixedSteps<'a, 'm, M: Model + 'm> {
    /// The run's track.
    fn track(&mut self) -> &mut Track<'a, 'm, M>;
    /// Attempts a step of `h` and, if the method succeeds, accepts it (ending at `end`): the
    /// flow after it, or inside `Ok` the method's failure, which [`advance_to`] may retry as
    /// two half steps. `Err` is a failure of the acceptance (divergence, an event's error).
    fn step(&mut self, h: f64, end: f64) -> Result<std::result::Result<Flow, Error>>;
    /// Takes `count` grid steps from index `n` as a bare loop; false when they must be retaken
    /// on the checked path (see the implementation for `Driver`).
    fn run_block(&mut self, dt: f64, n: u64, count: u64) -> bool;
}

impl<'a, 'm, M: Model, I: Integrator<M>> FixedSteps<'a, 'm, M> for Driver<'a, 'm, M, I> {
    fn track(&mut self) -> &mut Track<'a, 'm, M> {
        &mut self.track
    }

    #[inline]
    fn step(&mut self, h: f64, end: f64) -> Result<std::result::Result<Flow, Error>> {
        match self.attempt(h, None) {
            Ok(_) => self.accept(end).map(Ok),
            Err(error) => Ok(Err(error)),
        }
    }

    /// Takes `count` grid steps from index `n` as a bare loop — the same attempts at the same
    /// (t, h) as the checked path — and tests the divergence limit once, on the block's last
    /// state (a state that left the limit is infinite, NaN or still growing there; one that
    /// left it and came back within a block is not reported). Returns false when a step failed
    /// or the last state is outside the limit: the state, time and counts are then back at the
    /// block's start (the method restarted there) and the caller retakes the block on the
    /// checked path, which halves the failing step or names the diverging one.
    fn run_block(&mut self, dt: f64, n: u64, count: u64) -> bool {
        self.track.at.clone_from(&self.track.y);
        let stats = self.track.stats;
        let inside = bare_steps(
            &mut self.integrator,
            self.track.model,
            (self.track.t0, dt, n, count),
            (&mut self.track.y, &mut self.track.y_new),
            &mut self.track.stats,
            self.track.limit,
        );
        if inside {
            self.track.stats.steps += count;
            self.track.t = self.track.t0 + (n + count) as f64 * dt;
            self.track.grid = Some(n + count);
            self.track.f_start = false;
            return true;
        }
        std::mem::swap(&mut self.track.y, &mut self.track.at);
        self.track.stats = stats;
        self.integrator.restart(
            self.track.model,
            self.track.t,
            &self.track.y,
            &mut self.track.stats,
        );
        false
    }
}

impl<'a, 'm, M: Model, I: Integrator<M>> Driver<'a, 'm, M, I> {
    /// Takes `steps` steps of the grid t₀ + n·dt (n counted from `first`), recording per
    /// [`Recording`]. Returns early when an event stops the run.
    pub(crate) fn run_fixed(&mut self, dt: f64, first: u64, steps: u64) -> Result<()> {
        run(self, dt, first, steps)
    }
}

/// [`Driver::run_fixed`], once per model.
fn run<'a, 'm, M: Model + 'm>(
    d: &mut dyn FixedSteps<'a, 'm, M>,
    dt: f64,
    first: u64,
    steps: u64,
) -> Result<()> {
    let mut until_record = d.track().recording.every;
    let last = first.saturating_add(steps);
    let mut n = first;
    // Steps before this grid index go through the checked path (a block being retaken).
    let mut checked_until = first;
    let recording = !d.track().quiet && d.track().recording.save_at.is_none();
    while n < last {
        let block = (last - n)
            .min(BLOCK)
            .min(if recording { until_record } else { BLOCK });
        // Checked as the run goes: a run of `steps(u64::MAX)` stops at a divergence first.
        check_resolution(d.track().t0, dt, n, n + block)?;
        let taken = if n >= checked_until && block > 1 && d.track().plain() {
            if !d.run_block(dt, n, block) {
                checked_until = n + block;
                continue;
            }
            block
        } else {
            // Time as t₀ + n·dt, never accumulated: two runs that took the same steps are at
            // bit-identical times.
            let target = d.track().t0 + (n + 1) as f64 * dt;
            d.track().grid = Some(n + 1);
            loop {
                match advance_to(d, target)? {
                    Flow::Continue => break,
                    Flow::Changed => continue,
                    Flow::Stopped => return Ok(()),
                }
            }
            1
        };
        n += taken;
        if recording {
            d.track().record_grid(taken, &mut until_record, n == last);
        }
    }
    d.track().finish();
    Ok(())
}

/// Steps from the current time to `target`, halving a step whose implicit solve fails and
/// landing on any time event in between.
fn advance_to<'a, 'm, M: Model + 'm>(
    d: &mut dyn FixedSteps<'a, 'm, M>,
    target: f64,
) -> Result<Flow> {
    let track = d.track();
    track.pending.clear();
    track.pending.push((target, 0));
    let stop = track.watch.next_stop();
    if stop > track.t && stop < target {
        track.pending.push((stop, 0));
    }
    while let Some(&(end, depth)) = d.track().pending.last() {
        let h = end - d.track().t;
        if h == 0.0 {
            // Already there: a change event on a grid time returns here to finish the grid
            // step it ended. A step of length 0 is nothing to take (and M − 0·J, a DAE's
            // singular mass matrix, nothing to solve with).
            d.track().pending.pop();
            continue;
        }
        match d.step(h, end)? {
            Ok(flow) => {
                d.track().pending.pop();
                if flow != Flow::Continue {
                    return Ok(flow);
                }
            }
            Err(error) if error.is_retriable() && depth < d.track().max_halvings => {
                let track = d.track();
                track.stats.rejected += 1;
                let mid = track.t + 0.5 * h;
                track.pending.pop();
                track.pending.push((end, depth + 1));
                track.pending.push((mid, depth + 1));
            }
            Err(error) => return Err(error.with_halvings(depth)),
        }
    }
    Ok(Flow::Continue)
}

impl<M: Model> Track<'_, '_, M> {
    /// Records the grid step reached after `taken` more steps, at the recording interval (and
    /// at the run's `last` step).
    fn record_grid(&mut self, taken: u64, until_record: &mut u64, last: bool) {
        *until_record -= taken;
        if *until_record == 0 || last {
            self.push_sample();
            *until_record = self.recording.every;
            self.report(self.t);
        }
    }
}

/// Whether fixed steps of `dt` from grid index `first` to `last` (t = t₀ + n·dt) all advance the
/// time (one test per block of steps). Each grid time is rounded twice (n·dt, then t₀ +), by at
/// most one ulp of the largest magnitude on the way in all, so two neighbours differ by at least
/// dt − 2 ulp: more than two ulps of dt guarantees every step a positive length.
///
/// Errors: [`Error::InvalidInput`] naming `dt` when it is not that large.
fn check_resolution(t0: f64, dt: f64, first: u64, last: u64) -> Result<()> {
    let far = [
        t0,
        t0 + first as f64 * dt,
        t0 + last as f64 * dt,
        last as f64 * dt,
    ]
    .iter()
    .fold(0.0f64, |m, t| m.max(t.abs()));
    if dt > 2.0 * ulp(far) {
        return Ok(());
    }
    Err(Error::invalid(
        "dt",
        format!(
            "{dt:e} is below the resolution of t near {far:e} (one ulp there is {:e}): steps \
             would not advance the time; use a larger dt, or a start time nearer 0",
            ulp(far)
        ),
    ))
}

/// `count` steps of `integrator` from grid index `n` (t = t₀ + i·dt), as a bare loop; false as
/// soon as a step fails, or when the last state is outside `limit`. Small plain states (no heap
/// parts, at most 256 bytes) are stepped in local copies the optimiser keeps in registers, as a
/// hand-written loop's would be; the others in place. A function of its own, one call per block.
#[inline(never)]
fn bare_steps<M: Model, I: Integrator<M>>(
    integrator: &mut I,
    model: &M,
    grid: (f64, f64, u64, u64),
    (y, y_new): (&mut M::State, &mut M::State),
    stats: &mut Stats,
    limit: f64,
) -> bool {
    if std::mem::needs_drop::<M::State>() || std::mem::size_of::<M::State>() > 256 {
        return steps_in(integrator, model, grid, y, y_new, stats, limit);
    }
    let (mut a, mut b) = (y.clone(), y_new.clone());
    let mut counts = *stats;
    let local = (!std::mem::needs_drop::<I>() && std::mem::size_of::<I>() <= 1024)
        .then(|| integrator.duplicate())
        .flatten();
    let inside = match local {
        Some(mut copy) => {
            let inside = steps_in(&mut copy, model, grid, &mut a, &mut b, &mut counts, limit);
            *integrator = copy;
            inside
        }
        None => steps_in(integrator, model, grid, &mut a, &mut b, &mut counts, limit),
    };
    (*y, *y_new, *stats) = (a, b, counts);
    inside
}

#[inline(always)]
fn steps_in<M: Model, I: Integrator<M>>(
    integrator: &mut I,
    model: &M,
    (t0, dt, n, count): (f64, f64, u64, u64),
    y: &mut M::State,
    y_new: &mut M::State,
    stats: &mut Stats,
    limit: f64,
) -> bool {
    // The grid index as a float, exact below 2⁵³ (the same values as `i as f64`, without a
    // conversion per step); each step's end is the next one's start. Steps go in pairs, y → y_new
    // → y, so no state is swapped: with a swap a step, LLVM rotated a small state through extra
    // registers on the critical path (explicit-Euler Lorenz was 1.21× the bare integrator, 1.03×
    // in pairs; RK4 1.12× → 0.98×).
    let mut index = n as f64;
    let mut t = t0 + index * dt;
    let mut one = |from: &mut M::State, to: &mut M::State, stats: &mut Stats| {
        index += 1.0;
        let end = t0 + index * dt;
        let step = Step {
            t,
            h: end - t,
            y: from,
            tolerances: None,
            stats,
        };
        if integrator.attempt(model, step, to).is_err() {
            return false;
        }
        integrator.accept();
        t = end;
        true
    };
    for _ in 0..count / 2 {
        if !(one(y, y_new, stats) && one(y_new, y, stats)) {
            return false;
        }
    }
    if count % 2 == 1 {
        if !one(y, y_new, stats) {
            return false;
        }
        std::mem::swap(y, y_new);
    }
    within(y, limit)
}

/// Whether every component is within `limit` (NaN is not): one branch-free pass.
#[inline]
fn within<S: State>(state: &S, limit: f64) -> bool {
    state
        .as_slice()
        .iter()
        .fold(true, |ok, x| ok & (x.abs() <= limit))
}
