//! Differential–algebraic problems, M·y′ = f(t, y), with their references: Robertson in DAE form,
//! the Bari test set's chemical Akzo Nobel problem and transistor amplifier, and a pendulum in
//! Cartesian coordinates with its rod force as the algebraic component.
//!
//! Equations, constants, starts and references as `peers/notes/dae-problems.md` writes them out
//! (transcribed from the test set's Fortran, `chemakzo.f` rev. 1.2 and `transamp.f` rev. 1.3:
//! F. Mazzia and C. Magherini, *Test Set for Initial Value Problem Solvers*, release 2.4,
//! University of Bari, 2008), with the cross-checks of `scripts/reference_dae.py`.

use odyn::prelude::*;

/// Robertson's reaction (Hairer & Wanner, *Solving ODEs II*, §IV.10 and §VI.1) with the
/// conservation y₁ + y₂ + y₃ = 1 as its third row: the form of SUNDIALS' `idaRoberts_dns`.
#[system]
#[derive(Clone, Copy, Debug)]
pub struct RobertsonDae {
    /// Concentration of A.
    #[state]
    pub y1: f64,
    /// Concentration of B.
    #[state]
    pub y2: f64,
    /// Concentration of C, fixed by the conservation law.
    #[algebraic]
    pub y3: f64,
    /// Rate of A → B.
    #[param]
    pub k1: f64,
    /// Rate of B + C → A + C.
    #[param]
    pub k2: f64,
    /// Rate of 2B → B + C.
    #[param]
    pub k3: f64,
}

impl RobertsonDae {
    /// From A alone, y = (1, 0, 0), with Robertson's rates 0.04, 10⁴, 3·10⁷.
    pub fn classic() -> Self {
        RobertsonDae {
            y1: 1.0,
            y2: 0.0,
            y3: 0.0,
            k1: 0.04,
            k2: 1e4,
            k3: 3e7,
        }
    }
}

#[system]
impl RobertsonDae {
    fn derivative(&self) -> RobertsonDaeState {
        let slow = self.k1 * self.y1;
        let exchange = self.k2 * self.y2 * self.y3;
        RobertsonDaeState {
            y1: -slow + exchange,
            y2: slow - exchange - self.k3 * self.y2 * self.y2,
            y3: self.y1 + self.y2 + self.y3 - 1.0,
        }
    }
}

/// Robertson-DAE y(10¹¹): Radau IIA with 7 stages in 36-digit arithmetic, rtol 10⁻²⁴, on the
/// ODE form, whose solution is the DAE's (`peers/notes/dae-problems.md` §3,
/// `scripts/reference_dae.py`); the test set's `rober.f` agrees to 1.9·10⁻¹⁴.
pub const ROBERTSON_DAE_1E11: [f64; 3] = [
    2.083340149701294e-08,
    8.333360770334784e-14,
    0.9999999791665152,
];

/// The chemical Akzo Nobel problem (`chemakzo.f`): two reactants and CO₂ supplied through a gas
/// phase, five differential concentrations and one algebraic, y₆ = K_s·y₁·y₄ (an equilibrium),
/// index 1, from the consistent start to t = 180.
#[system]
#[derive(Clone, Copy, Debug)]
pub struct ChemAkzo {
    /// Concentration of FLB (mol/L).
    #[state]
    pub y1: f64,
    /// Concentration of CO₂ (mol/L).
    #[state]
    pub y2: f64,
    /// Concentration of FLBT (mol/L).
    #[state]
    pub y3: f64,
    /// Concentration of ZHU (mol/L).
    #[state]
    pub y4: f64,
    /// Concentration of ZLA (mol/L).
    #[state]
    pub y5: f64,
    /// Concentration of FLB·ZHU, in equilibrium (mol/L).
    #[algebraic]
    pub y6: f64,
}

impl ChemAkzo {
    /// The test set's consistent start (`init`): y₆ = K_s·0.444·0.007.
    pub fn start() -> Self {
        ChemAkzo {
            y1: 0.444,
            y2: 0.00123,
            y3: 0.0,
            y4: 0.007,
            y5: 0.0,
            y6: 115.83 * 0.444 * 0.007,
        }
    }
}

#[system]
impl ChemAkzo {
    fn derivative(&self) -> ChemAkzoState {
        let (k1, k2, k3, k4) = (18.7, 0.58, 0.09, 0.42);
        let (big_k, kla, ks, pco2, h) = (34.4, 3.3, 115.83, 0.9, 737.0);
        let root = self.y2.sqrt();
        let r1 = k1 * self.y1 * self.y1 * self.y1 * self.y1 * root;
        let r2 = k2 * self.y3 * self.y4;
        let r3 = k2 / big_k * self.y1 * self.y5;
        let r4 = k3 * self.y1 * self.y4 * self.y4;
        let r5 = k4 * self.y6 * self.y6 * root;
        let fin = kla * (pco2 / h - self.y2);
        ChemAkzoState {
            y1: ((-2.0 * r1 + r2) - r3) - r4,
            y2: ((-0.5 * r1 - r4) - 0.5 * r5) + fin,
            y3: (r1 - r2) + r3,
            y4: (-r2 + r3) - 2.0 * r4,
            y5: (r2 - r3) + r5,
            y6: ks * self.y1 * self.y4 - self.y6,
        }
    }
}

/// Chemical Akzo Nobel y(180): the test set's `chemakzo.f` `solut` (PSIDE on a Cray C90,
/// rtol = atol = 10⁻¹⁹); a 30-digit Radau IIA run agrees to 2·10⁻¹⁶.
pub const CHEMAKZO_REFERENCE: [f64; 6] = [
    0.1150794920661702e0,
    0.1203831471567715e-2,
    0.1611562887407974e0,
    0.3656156421249283e-3,
    0.1708010885264404e-1,
    0.4873531310307455e-2,
];

/// The transistor amplifier (`transamp.f`): eight node voltages, M·y′ = f(t, y) with the
/// singular, non-diagonal M of the capacitances C_k = k·10⁻⁶ F (rank 5: the sums of rows 1 + 2,
/// 4 + 5 and 7 + 8 are the algebraic node equations), driven by U_e(t) = 0.1·sin(200πt) V.
/// No component is algebraic by itself: the model gives `fn mass` and no `#[algebraic]` field,
/// and its start must be consistent (the test set's is).
#[system]
#[derive(Clone, Copy, Debug)]
pub struct Transamp {
    /// The node voltages U₁ … U₈ (V).
    #[state]
    pub u: [f64; 8],
}

impl Transamp {
    /// The test set's consistent start: (0, 3, 3, 6, 3, 3, 6, 0) V.
    pub fn start() -> Self {
        // U_b/(R₂/R₁ + 1) and U_b/(R₆/R₅ + 1), all four resistors 9 kΩ.
        let (ub, r1, r2) = (6.0, 9000.0, 9000.0);
        let half = ub / (r2 / r1 + 1.0);
        Transamp {
            u: [0.0, half, half, ub, half, half, ub, 0.0],
        }
    }
}

#[system]
impl Transamp {
    fn derivative(&self, t: f64) -> TransampState {
        let (ub, uf, alpha, beta) = (6.0, 0.026, 0.99, 1e-6);
        let (r0, rk) = (1000.0, 9000.0);
        let u = self.u;
        let input = 0.1 * (200.0 * std::f64::consts::PI * t).sin();
        let fac1 = beta * (((u[1] - u[2]) / uf).exp() - 1.0);
        let fac2 = beta * (((u[4] - u[5]) / uf).exp() - 1.0);
        TransampState {
            u: [
                (u[0] - input) / r0,
                u[1] / rk + (u[1] - ub) / rk + (1.0 - alpha) * fac1,
                u[2] / rk - fac1,
                (u[3] - ub) / rk + alpha * fac1,
                u[4] / rk + (u[4] - ub) / rk + (1.0 - alpha) * fac2,
                u[5] / rk - fac2,
                (u[6] - ub) / rk + alpha * fac2,
                u[7] / rk,
            ],
        }
    }

    /// The capacitances between the nodes (`transamp.f` `meval`).
    fn mass(&self) -> [[f64; 8]; 8] {
        let c = [1e-6, 2e-6, 3e-6, 4e-6, 5e-6];
        let mut m = [[0.0; 8]; 8];
        for (a, b, ck) in [(0, 1, c[0]), (3, 4, c[2]), (6, 7, c[4])] {
            m[a][a] = -ck;
            m[a][b] = ck;
            m[b][a] = ck;
            m[b][b] = -ck;
        }
        m[2][2] = -c[1];
        m[5][5] = -c[3];
        m
    }
}

/// Transistor amplifier y(0.2): the test set's `transamp.f` `solut` (PSIDE on a Cray C90,
/// rtol = atol = 10⁻¹⁴); SciPy's Radau at 10⁻¹³ on the reduced ODE agrees to 3.6·10⁻¹³.
pub const TRANSAMP_REFERENCE: [f64; 8] = [
    -0.5562145012262709e-002,
    0.3006522471903042e+001,
    0.2849958788608128e+001,
    0.2926422536206241e+001,
    0.2704617865010554e+001,
    0.2761837778393145e+001,
    0.4770927631616772e+001,
    0.1236995868091548e+001,
];

/// A point mass on a rod of length L about the origin, in Cartesian coordinates (y up), its
/// rod force λ·(x, y) the algebraic component: the length constraint differentiated twice
/// (index 1), with Baumgarte's drift control (J. Baumgarte, Comput. Methods Appl. Mech. Eng. 1
/// (1972) 1–16): the residual is g̈ + 2α·ġ + β²·g for g = (x² + y² − L²)/2, so a drift off
/// the position and velocity constraints decays at rates α, β instead of growing. On the exact
/// solution g = ġ = 0, so the trajectory is the pendulum's whatever α and β.
#[system]
#[derive(Clone, Copy, Debug)]
pub struct CartesianPendulum {
    /// Horizontal position (m).
    #[state]
    pub x: f64,
    /// Vertical position (m), up.
    #[state]
    pub y: f64,
    /// Horizontal velocity (m/s).
    #[state]
    pub u: f64,
    /// Vertical velocity (m/s).
    #[state]
    pub v: f64,
    /// The rod force per unit length (N/m), positive in tension.
    #[algebraic]
    pub lambda: f64,
    /// Mass (kg).
    pub m: f64,
    /// Rod length (m).
    pub length: f64,
    /// Gravity (m/s²).
    pub g: f64,
    /// Baumgarte's α (1/s): the residual has 2α·ġ; 0 with `beta` 0 leaves the index-1 form as
    /// it is.
    pub alpha: f64,
    /// Baumgarte's β (1/s): the residual has β²·g.
    pub beta: f64,
}

impl CartesianPendulum {
    /// m = 1 kg, L = 1 m, g = 9.81 m/s², released from rest at θ₀ = 2.5 rad from the downward
    /// vertical, λ = 0 as a guess for the consistent start to repair (it is m·g·cos θ₀/L);
    /// Baumgarte's gains `alpha`, `beta`.
    pub fn released(alpha: f64, beta: f64) -> Self {
        let theta: f64 = 2.5;
        CartesianPendulum {
            x: theta.sin(),
            y: -theta.cos(),
            u: 0.0,
            v: 0.0,
            lambda: 0.0,
            m: 1.0,
            length: 1.0,
            g: 9.81,
            alpha,
            beta,
        }
    }
}

#[system]
impl CartesianPendulum {
    fn derivative(&self) -> CartesianPendulumState {
        let (x, y, u, v, lambda) = (self.x, self.y, self.u, self.v, self.lambda);
        let r2 = x * x + y * y;
        let position = 0.5 * (r2 - self.length * self.length);
        let velocity = x * u + y * v;
        // x·u′ + y·v′ + u² + v² with m·u′ = −λx, m·v′ = −λy − m·g, times m.
        let acceleration = self.m * (u * u + v * v) - self.m * self.g * y - lambda * r2;
        CartesianPendulumState {
            x: u,
            y: v,
            u: -lambda * x / self.m,
            v: -lambda * y / self.m - self.g,
            lambda: acceleration
                + self.m * (2.0 * self.alpha * velocity + self.beta * self.beta * position),
        }
    }
}

/// The Cartesian pendulum's exact state (x, y, u, v, λ) at t = 10 for
/// [`CartesianPendulum::released`], from the angle form's solution in Jacobi elliptic functions
/// at 40 digits (`peers/notes/dae-problems.md` §4; θ(10) = 2.4627392257594350461,
/// θ′(10) = −0.66957139878127754846).
pub const PENDULUM_10: [f64; 5] = [
    0.6279010676602864,
    0.7782931640654904,
    0.5211228425252368,
    -0.4204245961695556,
    -7.186730081416545,
];

/// The Cartesian pendulum's exact state (x, y, u, v, λ) at t = 1, from the same source as
/// [`PENDULUM_10`].
pub const PENDULUM_1: [f64; 5] = [
    -0.8397213098423866,
    -0.543017607262036,
    -2.788618437697836,
    4.312313810524887,
    31.69944591875256,
];

/// The consistent start of [`CartesianPendulum::released`] (x, y, u, v, λ), λ₀ = m·g·cos θ₀/L
/// (`scripts/reference_dae.py`).
pub const PENDULUM_Y0: [f64; 5] = [
    0.5984721441039565,
    0.8011436155469337,
    0.0,
    0.0,
    -7.85921886851542,
];
