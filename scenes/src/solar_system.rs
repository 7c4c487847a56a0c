//! The outer solar system (Hairer, Lubich & Wanner 2006, §I.2.4, Table 2.1), its positions and
//! velocities `[Vector3<f64>; 6]`, and the same system one axis per array.
#![allow(
    clippy::excessive_precision,
    reason = "the data are quoted with the digits their source prints"
)]

use odyn::prelude::*;

/// Newtonian gravity between the six bodies of the outer solar system in 3-D, each axis an
/// array of its own: the form `examples/nbody.rs` used before state fields could be arrays of
/// vectors, kept to check [`SolarSystem`] against it bit for bit. Explicit methods only.
#[system(jacobian = false)]
#[derive(Clone, Copy, Debug)]
pub struct SolarSystemByAxis {
    /// x coordinates (AU).
    #[position]
    pub x: [f64; 6],
    /// y coordinates (AU).
    #[position]
    pub y: [f64; 6],
    /// z coordinates (AU).
    #[position]
    pub z: [f64; 6],
    /// x velocities (AU/day).
    #[velocity]
    pub u: [f64; 6],
    /// y velocities (AU/day).
    #[velocity]
    pub v: [f64; 6],
    /// z velocities (AU/day).
    #[velocity]
    pub w: [f64; 6],
    /// Masses (solar masses).
    pub m: [f64; 6],
    /// Gravitational constant.
    pub g: f64,
}

#[system]
impl SolarSystemByAxis {
    /// Each pair once: the force is computed for i < j and applied to both bodies.
    fn acceleration(&self) -> ([f64; 6], [f64; 6], [f64; 6]) {
        let mut ax = [0.0; 6];
        let mut ay = [0.0; 6];
        let mut az = [0.0; 6];
        for i in 0..6 {
            for j in (i + 1)..6 {
                let dx = self.x[j] - self.x[i];
                let dy = self.y[j] - self.y[i];
                let dz = self.z[j] - self.z[i];
                let r2 = dx * dx + dy * dy + dz * dz;
                let s = self.g / (r2 * r2.sqrt());
                ax[i] += self.m[j] * s * dx;
                ay[i] += self.m[j] * s * dy;
                az[i] += self.m[j] * s * dz;
                ax[j] -= self.m[i] * s * dx;
                ay[j] -= self.m[i] * s * dy;
                az[j] -= self.m[i] * s * dz;
            }
        }
        (ax, ay, az)
    }
}

impl SolarSystemByAxis {
    /// [`SolarSystem::outer`], each axis an array.
    pub fn outer() -> Self {
        let s = SolarSystem::outer();
        let SolarSystemByAxisState { x, y, z, u, v, w } = Self::by_axis(&s.state());
        SolarSystemByAxis {
            x,
            y,
            z,
            u,
            v,
            w,
            m: s.m,
            g: s.g,
        }
    }

    /// A state of [`SolarSystem`], each axis an array.
    pub fn by_axis(s: &SolarSystemState) -> SolarSystemByAxisState {
        let axis = |q: &[Vector3<f64>; 6], k: usize| std::array::from_fn(|i| q[i][k]);
        SolarSystemByAxisState {
            x: axis(&s.r, 0),
            y: axis(&s.r, 1),
            z: axis(&s.r, 2),
            u: axis(&s.v, 0),
            v: axis(&s.v, 1),
            w: axis(&s.v, 2),
        }
    }
}

/// Newtonian gravity between the six bodies of the outer solar system in 3-D (Hairer, Lubich &
/// Wanner, *Geometric Numerical Integration*, 2nd ed., 2006, §I.2.4, Table 2.1): the Sun (with
/// the inner planets' mass), Jupiter, Saturn, Uranus, Neptune and Pluto; masses relative to the
/// Sun, distances in AU, time in days. Positions and velocities are arrays of `Vector3`.
/// Explicit methods only: `#[system]` derives its 36 × 36 Jacobian in 0.9 s of this crate's
/// build, but then every `simulate()` on it compiles the implicit methods for a 36-component
/// faer-dense model too — 14 s more on the integration tests' build, their critical path
/// (measured 2026-11-27, one incremental build each; the tests run the implicit methods on a
/// three-body `[Vector3<f64>; 3]` model of their own instead).
#[system(jacobian = false)]
#[derive(Clone, Copy, Debug)]
pub struct SolarSystem {
    /// Positions (AU).
    #[position]
    pub r: [Vector3<f64>; 6],
    /// Velocities (AU/day).
    #[velocity]
    pub v: [Vector3<f64>; 6],
    /// Masses (solar masses).
    pub m: [f64; 6],
    /// Gravitational constant (AU³ per solar mass per day²).
    pub g: f64,
}

#[system]
impl SolarSystem {
    /// Each pair once: the force is computed for i < j and applied to both bodies (the
    /// arithmetic of [`SolarSystemByAxis`], one vector at a time).
    fn acceleration(&self) -> [Vector3<f64>; 6] {
        let mut a = [Vector3::<f64>::zeros(); 6];
        for i in 0..6 {
            for j in (i + 1)..6 {
                let d = self.r[j] - self.r[i];
                let r2 = d.x * d.x + d.y * d.y + d.z * d.z;
                let s = self.g / (r2 * r2.sqrt());
                a[i] += d * (self.m[j] * s);
                a[j] -= d * (self.m[i] * s);
            }
        }
        a
    }

    /// Kinetic plus potential energy, Σ ½mᵢ|vᵢ|² − Σ_{i<j} G mᵢ mⱼ / |rᵢ − rⱼ|.
    fn energy(&self) -> f64 {
        let mut e = 0.0;
        for i in 0..6 {
            e += 0.5 * self.m[i] * self.v[i].norm_squared();
            for j in (i + 1)..6 {
                e -= self.g * self.m[i] * self.m[j] / (self.r[j] - self.r[i]).norm();
            }
        }
        e
    }
}

impl SolarSystem {
    /// The outer solar system on 5 September 1994 (HLW Table 2.1), G = 2.95912208286·10⁻⁴, moved
    /// to its barycentric frame (the table's data are heliocentric, so the whole system would
    /// drift by ~1.4 AU over 2·10⁵ days).
    pub fn outer() -> Self {
        let mut system = SolarSystem {
            r: [
                Vector3::new(0.0, 0.0, 0.0),
                Vector3::new(-3.5023653, -3.8169847, -1.5507963),
                Vector3::new(9.0755314, -3.0458353, -1.6483708),
                Vector3::new(8.3101420, -16.2901086, -7.2521278),
                Vector3::new(11.4707666, -25.7294829, -10.8169456),
                Vector3::new(-15.5387357, -25.2225594, -3.1902382),
            ],
            v: [
                Vector3::new(0.0, 0.0, 0.0),
                Vector3::new(0.00565429, -0.00412490, -0.00190589),
                Vector3::new(0.00168318, 0.00483525, 0.00192462),
                Vector3::new(0.00354178, 0.00137102, 0.00055029),
                Vector3::new(0.00288930, 0.00114527, 0.00039677),
                Vector3::new(0.00276725, -0.00170702, -0.00136504),
            ],
            m: [
                1.00000597682,
                0.000954786104043,
                0.000285583733151,
                0.0000437273164546,
                0.0000517759138449,
                1.0 / 1.3e8,
            ],
            g: 2.95912208286e-4,
        };
        let total: f64 = system.m.iter().sum();
        let m = system.m;
        for q in [&mut system.r, &mut system.v] {
            // Axis by axis, body by body: the sums of the earlier form, in its order.
            for k in 0..3 {
                let centre = q.iter().zip(&m).map(|(q, m)| q[k] * m).sum::<f64>() / total;
                q.iter_mut().for_each(|q| q[k] -= centre);
            }
        }
        system
    }

    /// Total angular momentum Σ mᵢ rᵢ × vᵢ.
    pub fn angular_momentum(&self, s: &SolarSystemState) -> Vector3<f64> {
        let mut l = Vector3::zeros();
        for i in 0..6 {
            l += self.m[i] * s.r[i].cross(&s.v[i]);
        }
        l
    }
}
