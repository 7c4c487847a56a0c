//! What the errors say about their causes: why an adaptive step was rejected, why a Newton
//! iteration failed, the advice the messages give for each, and how they write sizes and counts.

use crate::Method;

/// Why an adaptive run's last attempt at a step was rejected (see [`Error::StepSizeTooSmall`](crate::Error::StepSizeTooSmall)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Rejection {
    /// Its error estimate exceeded the tolerances.
    ErrorTest,
    /// The matrix I − γh·J of its linear solves was singular.
    SingularMatrix,
    /// Its Newton iteration failed (BDF, implicit Euler).
    Newton,
    /// None yet: the step size proposed was already too small.
    None,
}

/// What a step size that fell to nothing says about the problem.
pub(super) fn step_advice(
    method: Method,
    rejection: Rejection,
    dt_min: bool,
    large_t: bool,
) -> String {
    if dt_min {
        return "lower `dt_min`, or see why the method needs steps that small there".to_owned();
    }
    let mut advice = match (method.needs_jacobian(), rejection) {
        (false, _) => "the problem is probably stiff here (use an implicit method: Rodas5P or \
                       Bdf), or its solution blows up or jumps at t"
            .to_owned(),
        (true, Rejection::SingularMatrix) => "the matrix I − γh·J was singular at every step \
             size tried: ∂f/∂y has an eigenvalue that keeps pace with 1/(γh) — check the \
             Jacobian at this state"
            .to_owned(),
        (true, Rejection::Newton) => "Newton's method failed at every step size tried: f is \
             not smooth here (a switch such as `abs`, `signum`, `min`/`max` or an `if` on the \
             state), or the solution blows up at t"
            .to_owned(),
        (true, _) => "the error estimate stays above the tolerances however short the step: f \
             switches abruptly here (`abs`, `signum`, `min`/`max` or an `if` on the state, \
             which no step resolves: stop the run there with an event and restart from it), the \
             solution blows up at t, or the tolerances ask for more than rounding allows (an \
             atol far below ε times the values a component is computed from, such as 1e-18 on \
             a component fixed by a conservation law among values of order 1: loosen atol)"
            .to_owned(),
    };
    if large_t {
        advice.push_str(
            "; or t is so large there that its floats are coarse: start the run nearer 0",
        );
    }
    advice
}

/// Why an attempt at an implicit step's Newton iteration failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum NewtonFailure {
    /// It ran out of iterations (`NewtonOptions::max_iterations`) while still converging.
    Iterations,
    /// Its updates stopped shrinking: the step is too large for the nonlinearity there.
    Diverging,
    /// The Newton matrix I − h·J was singular.
    Singular,
    /// The model's derivative or Jacobian returned NaN or infinity at an iterate.
    NotFinite,
    /// The model's values were finite but the Newton update was not: the solve overflowed (the
    /// model's scales, such as a mass of 1e-300 beside a stiffness of 100, span more than f64
    /// holds) or met a singular matrix its factorization did not see.
    UpdateNotFinite,
    /// The quasi-Newton solve found no step along its direction, down to a thousandth of it,
    /// that lowered the implicit Euler objective, with every value finite: the forces stiffen
    /// faster over the step than the link Laplacian (made from the Jacobian at the run's start)
    /// expects.
    LineSearch,
}

impl NewtonFailure {
    /// What failed and the option that addresses it.
    pub(super) fn explain(self, iters: u32, halvings: u32) -> String {
        match self {
            NewtonFailure::Iterations => format!(
                "it was still converging when its {iters} iterations ran out; raise \
                 `NewtonOptions::max_iterations`"
            ),
            NewtonFailure::LineSearch => format!(
                "no step along the quasi-Newton direction lowered the implicit Euler objective \
                 (the forces stiffen over the step faster than the link Laplacian from the run's \
                 start expects); reduce dt, raise `NewtonOptions::max_halvings` (now \
                 {halvings}) so the step can be split further, or use `ParticleSolve::Newton`"
            ),
            NewtonFailure::Diverging | NewtonFailure::Singular => format!(
                "{}; reduce dt, or raise `NewtonOptions::max_halvings` (now {halvings}) so the \
                 step can be split further",
                if self == NewtonFailure::Singular {
                    "the Newton matrix I − h·J was singular"
                } else {
                    "its updates stopped shrinking, the step is too large for the nonlinearity \
                     here"
                }
            ),
            NewtonFailure::NotFinite => "the model's derivative or Jacobian returned NaN or \
                infinity at an iterate; check its parameters and state"
                .to_owned(),
            NewtonFailure::UpdateNotFinite => "the model's values were finite but the Newton \
                update was not: the linear solve overflowed or its matrix is singular; check \
                that the model's scales (masses against stiffnesses, say) are within f64's \
                range of each other, or reduce dt"
                .to_owned(),
        }
    }
}

/// `bytes` in SI units with two significant digits or more: `512 B`, `4.3 GB`, `79 TB`.
pub(crate) fn bytes_text(bytes: u128) -> String {
    const UNITS: [&str; 9] = ["B", "kB", "MB", "GB", "TB", "PB", "EB", "ZB", "YB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 999.5 && unit + 1 < UNITS.len() {
        value /= 1000.0;
        unit += 1;
    }
    if unit == 0 || value >= 9.95 {
        format!("{value:.0} {}", UNITS[unit])
    } else {
        format!("{value:.1} {}", UNITS[unit])
    }
}

/// A count as a person reads it: exact below a million, else `1.1e12`.
pub(crate) fn count_text(count: u64) -> String {
    if count < 1_000_000 {
        count.to_string()
    } else {
        format!("{:.1e}", count as f64)
    }
}

/// ", its accepted steps averaged … s: about … more to go", or nothing when no step was
/// accepted.
pub(super) fn projection(t: f64, t_end: f64, mean_step: f64) -> String {
    if mean_step > 0.0 {
        format!(
            "; its accepted steps averaged {mean_step:.1e} s, so the rest would take about \
             {:.1e} more",
            (t_end - t) / mean_step
        )
    } else {
        String::new()
    }
}

/// What to do about a spent step budget, by the method's kind. When the rest of the run would
/// take more than a thousand times the budget at the mean step so far, raising the budget is
/// not offered, and for an implicit method the step size is named as a time scale to check.
pub(super) fn max_steps_advice(
    method: Method,
    t: f64,
    t_end: f64,
    mean_step: f64,
    steps: u64,
) -> String {
    let hopeless = mean_step > 0.0 && (t_end - t) / mean_step > 1e3 * steps as f64;
    let raise = if hopeless {
        String::new()
    } else {
        ", or raise `max_steps`".to_string()
    };
    if !method.needs_jacobian() {
        return format!(
            "the problem is probably stiff for this method (use an implicit one: Rodas5P or \
             Bdf){raise}"
        );
    }
    let scale = if hopeless {
        format!(
            ", or the model's fastest time scale is as short as its steps, about {mean_step:.1e} \
             s (check its parameters and units: a stiffness over a mass of \
             1/({mean_step:.0e} s)² makes one)"
        )
    } else {
        String::new()
    };
    format!(
        "its steps stayed short, so f is probably not smooth there (a switch such as `abs`, \
         `signum`, `min`/`max` or an `if` on the state, which a step straddles over and over: \
         stop the run there with an event and restart from it), or the tolerances ask for more \
         than rounding allows (loosen atol){scale}{raise}"
    )
}

#[cfg(test)]
mod tests {
    use super::{bytes_text, count_text};

    #[test]
    fn sizes_read_compactly() {
        assert_eq!(bytes_text(512), "512 B");
        assert_eq!(bytes_text(4_294_967_296), "4.3 GB");
        assert_eq!(bytes_text(79_164_837_199_872), "79 TB");
        assert_eq!(bytes_text(999_999), "1.0 MB");
        assert_eq!(bytes_text(u128::MAX), "340282366920938 YB");
        assert_eq!(count_text(999_999), "999999");
        assert_eq!(count_text(1 << 40), "1.1e12");
    }
}
