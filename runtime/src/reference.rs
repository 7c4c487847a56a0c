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

/// A Kepler orbit, r̈ = −GM·r/|r|³, with its pericentre on the +x axis at t = 0 and motion
/// counter-clockwise: position and velocity at any time from Kepler's equation E − e·sin E = M.
///
/// Reference: H. D. Curtis, *Orbital Mechanics for Engineering Students*, 3rd ed., §3.4.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KeplerOrbit {
    /// Gravitational parameter GM > 0.
    pub gm: f64,
    /// Semi-major axis a > 0.
    pub a: f64,
    /// Eccentricity, 0 ≤ e < 1.
    pub e: f64,
}

impl KeplerOrbit {
    /// The orbital period 2π·√(a³/GM).
    pub fn period(&self) -> f64 {
        std::f64::consts::TAU * (self.a.powi(3) / self.gm).sqrt()
    }

    /// ((x, y), (vx, vy)) at time t.
    pub fn state_at(&self, t: f64) -> ([f64; 2], [f64; 2]) {
        let n = (self.gm / self.a.powi(3)).sqrt();
        let mean = (n * t).rem_euclid(std::f64::consts::TAU);
        // Newton on E − e·sin E − M from E = M + e·sin M converges in a few steps for e < 1.
        let mut ecc = mean + self.e * mean.sin();
        for _ in 0..50 {
            let delta = (ecc - self.e * ecc.sin() - mean) / (1.0 - self.e * ecc.cos());
            ecc -= delta;
            if delta.abs() < 1e-15 {
                break;
            }
        }
        let b = self.a * (1.0 - self.e * self.e).sqrt();
        let rate = n / (1.0 - self.e * ecc.cos());
        let (sin, cos) = ecc.sin_cos();
        (
            [self.a * (cos - self.e), b * sin],
            [-self.a * sin * rate, b * cos * rate],
        )
    }

    /// Specific energy −GM/(2a).
    pub fn energy(&self) -> f64 {
        -self.gm / (2.0 * self.a)
    }
}

#[cfg(test)]
mod tests {
    use super::{DampedOscillator, KeplerOrbit};

    /// The closed form conserves energy and angular momentum and closes after one period; at
    /// t = 0 it starts at the pericentre a(1 − e) with the vis-viva speed.
    #[test]
    fn kepler_orbit_is_consistent() {
        let orbit = KeplerOrbit {
            gm: 1.0,
            a: 1.0,
            e: 0.5,
        };
        let ([x, y], [vx, vy]) = orbit.state_at(0.0);
        assert_eq!((x, y), (0.5, 0.0));
        assert!(vx.abs() < 1e-15 && (vy - 3f64.sqrt()).abs() < 1e-14);
        let l0 = x * vy - y * vx;
        for t in [0.3, 1.7, 4.0, 100.0] {
            let ([x, y], [vx, vy]) = orbit.state_at(t);
            let energy = 0.5 * (vx * vx + vy * vy) - 1.0 / (x * x + y * y).sqrt();
            assert!((energy - orbit.energy()).abs() < 1e-12, "t = {t}");
            assert!((x * vy - y * vx - l0).abs() < 1e-12, "t = {t}");
        }
        let ([x, y], _) = orbit.state_at(orbit.period());
        assert!((x - 0.5).abs() < 1e-12 && y.abs() < 1e-12);
    }

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
