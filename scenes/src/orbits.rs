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
/// eq. (10.12); problem PLEI of the Bari test set). Explicit methods only (`jacobian = false`):
/// the macro would differentiate the pair loop, but nothing that runs this scene needs a stiff
/// method, and a 28 × 28 Jacobian would be compiled into every test and bench that uses it.
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
