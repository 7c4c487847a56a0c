//! Closed-form solutions used as references by tests, examples and error measurements.

/// The linear oscillator m·ẍ = −k·x − b·ẋ, solved exactly.
///
/// Reference: any mechanics text, e.g. L. D. Landau & E. M. Lifshitz, *Mechanics*, 3rd ed., §25.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DampedOscillator {
    /// Stiffness k > 0.
    pub k: f64,
    /// Damping coefficient b ≥ 0.
    pub b: f64,
    /// Mass m > 0.
    pub m: f64,
}

impl DampedOscillator {
    /// (x(t), ẋ(t)) from x(0) = x0, ẋ(0) = v0, in every damping regime.
    pub fn state_at(&self, x0: f64, v0: f64, t: f64) -> (f64, f64) {
        let gamma = self.b / (2.0 * self.m);
        let omega0_sq = self.k / self.m;
        let disc = omega0_sq - gamma * gamma;
        let decay = (-gamma * t).exp();
        if disc > 0.0 {
            // Underdamped: x = e^{−γt}(A cos ωt + B sin ωt).
            let w = disc.sqrt();
            let (a, b) = (x0, (v0 + gamma * x0) / w);
            let (s, c) = (w * t).sin_cos();
            let x = decay * (a * c + b * s);
            let v = decay * ((b * w - gamma * a) * c - (a * w + gamma * b) * s);
            (x, v)
        } else if disc < 0.0 {
            // Overdamped: x = e^{−γt}(A cosh μt + B sinh μt).
            let mu = (-disc).sqrt();
            let (a, b) = (x0, (v0 + gamma * x0) / mu);
            let (s, c) = ((mu * t).sinh(), (mu * t).cosh());
            let x = decay * (a * c + b * s);
            let v = decay * ((b * mu - gamma * a) * c + (a * mu - gamma * b) * s);
            (x, v)
        } else {
            // Critically damped: x = e^{−γt}(A + B t).
            let (a, b) = (x0, v0 + gamma * x0);
            (decay * (a + b * t), decay * (b - gamma * (a + b * t)))
        }
    }

    /// Mechanical energy ½m·v² + ½k·x².
    pub fn energy(&self, x: f64, v: f64) -> f64 {
        0.5 * self.m * v * v + 0.5 * self.k * x * x
    }
}

#[cfg(test)]
mod tests {
    use super::DampedOscillator;

    /// The closed form satisfies its own ODE: check m·ẍ + b·ẋ + k·x = 0 by central differences.
    #[test]
    fn satisfies_the_equation_in_every_regime() {
        for b in [0.0, 0.5, 2.0 * 50f64.sqrt(), 40.0] {
            let osc = DampedOscillator { k: 50.0, b, m: 1.0 };
            for t in [0.1, 0.7, 2.3] {
                let h = 1e-4;
                let (x, v) = osc.state_at(1.0, 0.3, t);
                let (_, vp) = osc.state_at(1.0, 0.3, t + h);
                let (_, vm) = osc.state_at(1.0, 0.3, t - h);
                let (xp, _) = osc.state_at(1.0, 0.3, t + h);
                let (xm, _) = osc.state_at(1.0, 0.3, t - h);
                let accel = (vp - vm) / (2.0 * h);
                assert!(
                    (osc.m * accel + b * v + osc.k * x).abs() < 1e-5,
                    "b = {b}, t = {t}"
                );
                assert!(((xp - xm) / (2.0 * h) - v).abs() < 1e-5, "b = {b}, t = {t}");
            }
            assert_eq!(osc.state_at(1.0, 0.3, 0.0).0, 1.0);
            assert!((osc.state_at(1.0, 0.3, 0.0).1 - 0.3).abs() < 1e-15);
        }
    }
}
