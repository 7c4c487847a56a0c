//! Orbits: Kepler's problem, the Arenstorf orbit and the Pleiades, with their references.
#![allow(
    clippy::excessive_precision,
    reason = "the references are quoted with the digits their sources print"
)]

use odyn::prelude::*;

/// The planar Kepler problem, r̈ = −GM·r/|r|³, with vector state.
#[system(integrator = Leapfrog, dt = 0.01)]
#[derive(Clone, Copy, Debug)]
pub struct Kepler {
    /// Position.
    #[position]
    pub r: Vector2<f64>,
    /// Velocity.
    #[velocity]
    pub v: Vector2<f64>,
    /// Gravitational parameter GM.
    pub gm: f64,
}

#[system]
impl Kepler {
    fn acceleration(&self) -> Vector2<f64> {
        -self.gm * self.r / self.r.norm().powi(3)
    }

    /// Energy per unit mass, ½|v|² − GM/|r| (conserved).
    pub fn energy(&self) -> f64 {
        0.5 * self.v.norm_squared() - self.gm / self.r.norm()
    }
}

/// The Arenstorf orbit: a satellite in the rotating frame of the Earth–Moon system, whose
/// solution is periodic (Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.0, eq. (0.1)). Written
/// as `scripts/reference_adaptive.py` writes it, so both evaluate f identically.
#[system(integrator = Dop853)]
#[derive(Clone, Copy, Debug)]
pub struct Arenstorf {
    /// First coordinate in the rotating frame.
    #[position]
    pub y1: f64,
    /// Second coordinate.
    #[position]
    pub y2: f64,
    /// y1′.
    #[velocity]
    pub v1: f64,
    /// y2′.
    #[velocity]
    pub v2: f64,
    /// The Moon's mass fraction μ.
    pub mu: f64,
}

#[system]
impl Arenstorf {
    fn acceleration(&self) -> (f64, f64) {
        let mu = self.mu;
        let mup = 1.0 - self.mu;
        let d1 = ((self.y1 + mu).powi(2) + self.y2.powi(2)).powf(1.5);
        let d2 = ((self.y1 - mup).powi(2) + self.y2.powi(2)).powf(1.5);
        (
            self.y1 + 2.0 * self.v2 - mup * (self.y1 + mu) / d1 - mu * (self.y1 - mup) / d2,
            self.y2 - 2.0 * self.v1 - mup * self.y2 / d1 - mu * self.y2 / d2,
        )
    }
}

impl Arenstorf {
    /// The periodic orbit of HNW I, §II.0: μ = 0.012277471, from (0.994, 0) with
    /// y2′(0) = −2.00158510637908252240537862224.
    pub fn orbit() -> Self {
        Arenstorf {
            y1: 0.994,
            y2: 0.0,
            v1: 0.0,
            v2: -2.001_585_106_379_082_4,
            mu: 0.012_277_471,
        }
    }

    /// fl(T), T = 17.0652165601579625588917206249 (HNW I, eq. (0.2)).
    pub const PERIOD: f64 = 17.065_216_560_157_964;

    /// y(fl(T)) from [`Arenstorf::orbit`]'s f64 data: Taylor series at 50 digits
    /// (`scripts/reference_adaptive.py`), layout (y1, y2, y1′, y2′).
    pub const AT_PERIOD: [f64; 4] = [
        9.939_999_999_999_088_5e-1,
        -3.030_943_022_982_418_5e-13,
        -4.928_536_581_055_052_6e-11,
        -2.001_585_106_393_270_1,
    ];
}

/// The Pleiades: seven bodies in the plane under Newtonian gravity, G = 1 (HNW I, §II.10,
/// eq. (10.12); problem PLEI of the Bari test set). Explicit methods only: the loops over the
/// bodies are outside what the Jacobian generator differentiates.
#[system(jacobian = false)]
#[derive(Clone, Copy, Debug)]
pub struct Pleiades {
    /// x coordinates.
    #[position]
    pub x: [f64; 7],
    /// y coordinates.
    #[position]
    pub y: [f64; 7],
    /// x velocities.
    #[velocity]
    pub u: [f64; 7],
    /// y velocities.
    #[velocity]
    pub v: [f64; 7],
    /// Masses.
    pub m: [f64; 7],
}

#[system]
impl Pleiades {
    /// Each pair once: the force is computed for i < j and applied to both bodies.
    fn acceleration(&self) -> ([f64; 7], [f64; 7]) {
        let mut ax = [0.0; 7];
        let mut ay = [0.0; 7];
        for i in 0..7 {
            for j in (i + 1)..7 {
                let dx = self.x[j] - self.x[i];
                let dy = self.y[j] - self.y[i];
                let r2 = dx * dx + dy * dy;
                let w = 1.0 / (r2 * r2.sqrt());
                ax[i] += self.m[j] * w * dx;
                ay[i] += self.m[j] * w * dy;
                ax[j] -= self.m[i] * w * dx;
                ay[j] -= self.m[i] * w * dy;
            }
        }
        (ax, ay)
    }
}

impl Pleiades {
    /// The test set's initial state (HNW I, §II.10, eq. (10.13)).
    pub fn start() -> Self {
        Pleiades {
            x: [3.0, 3.0, -1.0, -3.0, 2.0, -2.0, 2.0],
            y: [3.0, -3.0, 2.0, 0.0, 0.0, -4.0, 4.0],
            u: [0.0, 0.0, 0.0, 0.0, 0.0, 1.75, -1.5],
            v: [0.0, 0.0, 0.0, -1.25, 1.0, 0.0, 0.0],
            m: [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0],
        }
    }

    /// y(3) from [`Pleiades::start`]: Taylor series at 44 digits
    /// (`scripts/reference_adaptive.py`), layout x₁…x₇, y₁…y₇, ẋ₁…ẋ₇, ẏ₁…ẏ₇.
    pub const AT_3: [f64; 28] = [
        3.706_139_143_970_512_7e-1,
        3.237_284_092_057_233_2,
        -3.222_559_032_418_323_5,
        6.597_091_455_775_308e-1,
        3.425_581_707_156_579_7e-1,
        1.562_172_101_400_631_1,
        -7.003_092_922_212_494_9e-1,
        -3.943_437_585_517_392_2,
        -3.271_380_973_972_549_9,
        5.225_081_843_456_544,
        -2.590_612_434_977_469_3,
        1.198_213_693_392_274_7,
        -2.429_682_344_935_823_5e-1,
        1.091_449_240_428_979_7,
        3.417_003_806_314_314_7,
        1.354_584_501_625_501_1,
        -2.590_065_597_810_775_6,
        2.025_053_734_714_241_2,
        -1.155_815_100_160_449_1,
        -8.072_988_170_223_022_2e-1,
        5.952_396_354_208_718_8e-1,
        -3.741_244_961_234_008_4,
        3.773_459_685_750_629_2e-1,
        9.386_858_869_551_079_1e-1,
        3.667_922_227_200_569_6e-1,
        -3.474_046_353_808_494_2e-1,
        2.344_915_448_180_937_1,
        -1.947_020_434_263_292,
    ];
}

/// Newtonian gravity between the six bodies of the outer solar system in 3-D, each axis an
/// array of its own: the form `examples/nbody.rs` used before state fields could be arrays of
/// vectors, kept to check [`SolarSystem`] against it bit for bit. Explicit methods only (its
/// Jacobian would be the same as [`SolarSystem`]'s).
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
        let axis = |q: &[Vector3<f64>; 6], k: usize| std::array::from_fn(|i| q[i][k]);
        SolarSystemByAxis {
            x: axis(&s.r, 0),
            y: axis(&s.r, 1),
            z: axis(&s.r, 2),
            u: axis(&s.v, 0),
            v: axis(&s.v, 1),
            w: axis(&s.v, 2),
            m: s.m,
            g: s.g,
        }
    }
}

/// Newtonian gravity between the six bodies of the outer solar system in 3-D (Hairer, Lubich &
/// Wanner, *Geometric Numerical Integration*, 2nd ed., 2006, §I.2.4, Table 2.1): the Sun (with
/// the inner planets' mass), Jupiter, Saturn, Uranus, Neptune and Pluto; masses relative to the
/// Sun, distances in AU, time in days. Positions and velocities are arrays of `Vector3`.
#[system]
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
