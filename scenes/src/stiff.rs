//! Stiff problems: van der Pol and four problems of the Bari test set (Mazzia & Magherini, *Test
//! Set for Initial Value Problem Solvers*, release 2.4, 2008), with their references.
#![allow(
    clippy::excessive_precision,
    reason = "the references are quoted with the digits their sources print"
)]

use odyn::prelude::*;

/// Robertson's y(1e5): the 36-digit Radau IIA run of `scripts/reference_stiff.py` (agrees with the
/// test set's value to 2e-14).
pub const ROBERTSON_1E5: [f64; 3] = [
    1.786_592_114_209_946_4e-2,
    7.274_751_468_436_319e-8,
    9.821_340_061_103_858e-1,
];

/// Robertson's y(1e11): the test set's `rober.f` reference (RADAU5 at rtol 1.1e-18 in extended
/// precision).
pub const ROBERTSON_1E11: [f64; 3] = [
    0.208_334_014_970_125_5e-7,
    0.833_336_077_033_471_3e-13,
    0.999_999_979_166_505,
];

/// HIRES at t = 321.8122: the test set's `hires.f` reference (RADAU5 in quadruple precision).
pub const HIRES_REFERENCE: [f64; 8] = [
    0.737_131_257_332_566_8e-3,
    0.144_248_572_631_618_5e-3,
    0.588_872_974_096_757_5e-4,
    0.117_565_134_328_314_9e-2,
    0.238_635_619_883_133_1e-2,
    0.623_896_825_274_279_6e-2,
    0.284_999_839_518_576_9e-2,
    0.285_000_160_481_423_1e-2,
];

/// POLLU at t = 60: the test set's `pollu.f` reference (RADAU5 in quadruple precision).
pub const POLLU_REFERENCE: [f64; 20] = [
    0.564_625_548_002_276_9e-1,
    0.134_248_413_042_233_9,
    0.413_973_433_109_942_7e-8,
    0.552_314_020_748_435_9e-2,
    0.201_897_726_230_219_6e-6,
    0.146_454_186_349_396_6e-6,
    0.778_424_911_899_796_4e-1,
    0.324_507_535_339_601_8,
    0.749_401_338_388_040_6e-2,
    0.162_229_315_730_156_1e-7,
    0.113_586_383_325_707_5e-7,
    0.223_050_597_572_135_9e-2,
    0.208_716_288_279_863e-3,
    0.139_692_101_684_015_8e-4,
    0.896_488_485_689_829_5e-2,
    0.435_284_636_933_010_3e-17,
    0.689_921_969_626_340_5e-2,
    0.100_780_303_736_594_6e-3,
    0.177_214_651_396_998_4e-5,
    0.568_294_329_231_639_2e-4,
];

/// OREGO at t = 360: the test set's `orego.f` reference (RADAU5 in quadruple precision); SciPy's
/// Radau at rtol 1e-13 agrees to 1.3e-13 relative (`scripts/reference_stiff.py`).
pub const OREGO_REFERENCE: [f64; 3] = [
    0.100_081_487_031_852_3e1,
    0.122_817_852_154_991_7e4,
    0.132_055_494_284_670_6e3,
];

/// van der Pol, μ = 1000, at t = 2000: the test set's `vdpolm.f` reference (problem VDPOLM).
pub const VAN_DER_POL_2000: [f64; 2] = [0.170_616_773_217_046_9e1, -0.892_809_701_024_812_5e-3];

/// A → B (k₁ = 0.04), B + C → A + C (k₂ = 10⁴), 2B → B + C (k₃ = 3·10⁷) (Robertson 1966), the
/// classic stiff test problem; the rates are `#[param]`s, so ∂f/∂k and the sensitivities to
/// them are generated too (the `fit_robertson` example recovers them from noisy data).
#[system(integrator = ImplicitEuler)]
#[derive(Clone, Copy, Debug)]
pub struct Robertson {
    /// Concentration of A.
    #[state]
    pub a: f64,
    /// Concentration of B.
    #[state]
    pub b: f64,
    /// Concentration of C.
    #[state]
    pub c: f64,
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

impl Robertson {
    /// Robertson's rates from A alone: a = 1, b = c = 0, k₁ = 0.04, k₂ = 10⁴, k₃ = 3·10⁷ (the
    /// test set's `rober.f`).
    pub fn classic() -> Self {
        Robertson {
            a: 1.0,
            b: 0.0,
            c: 0.0,
            k1: 0.04,
            k2: 1e4,
            k3: 3e7,
        }
    }
}

#[system]
impl Robertson {
    fn derivative(&self) -> RobertsonState {
        let slow = self.k1 * self.a;
        let exchange = self.k2 * self.b * self.c;
        let fast = self.k3 * self.b * self.b;
        RobertsonState {
            a: -slow + exchange,
            b: slow - exchange - fast,
            c: fast,
        }
    }
}

/// The Oregonator (Field & Noyes 1974; Hairer & Wanner, *Solving ODEs II*, §IV.10): the
/// Belousov–Zhabotinsky reaction's three intermediates, as in the test set's `orego.f`; from
/// (1, 2, 3) to t = 360 it goes round its limit cycle with concentrations over six orders of
/// magnitude.
#[system]
#[derive(Clone, Copy, Debug)]
pub struct Orego {
    /// The three concentrations.
    #[state]
    pub y: [f64; 3],
}

#[system]
impl Orego {
    fn derivative(&self) -> OregoState {
        let y = self.y;
        OregoState {
            y: [
                77.27 * (y[1] + y[0] * (1.0 - 8.375e-6 * y[0] - y[1])),
                (y[2] - (1.0 + y[0]) * y[1]) / 77.27,
                0.161 * (y[0] - y[2]),
            ],
        }
    }
}

/// HIRES (Schäfer 1975; Hairer & Wanner, *Solving ODEs II*, §IV.10), as in the test set's
/// `hires.f`.
#[system]
#[derive(Clone, Copy, Debug)]
pub struct Hires {
    /// The eight concentrations.
    #[state]
    pub y: [f64; 8],
}

#[system]
impl Hires {
    fn derivative(&self) -> HiresState {
        let y = self.y;
        let bind = 280.0 * y[5] * y[7];
        HiresState {
            y: [
                -1.71 * y[0] + 0.43 * y[1] + 8.32 * y[2] + 0.0007,
                1.71 * y[0] - 8.75 * y[1],
                -10.03 * y[2] + 0.43 * y[3] + 0.035 * y[4],
                8.32 * y[1] + 1.71 * y[2] - 1.12 * y[3],
                -1.745 * y[4] + 0.43 * y[5] + 0.43 * y[6],
                -bind + 0.69 * y[3] + 1.71 * y[4] - 0.43 * y[5] + 0.69 * y[6],
                bind - 1.81 * y[6],
                -bind + 1.81 * y[6],
            ],
        }
    }
}

/// POLLU, the air-pollution model of Verwer (SIAM J. Sci. Comput. 15, 1994): 20 species, 25
/// reactions, as in the test set's `pollu.f` (transcribed through `scripts/reference_stiff.py`).
#[system]
#[derive(Clone, Copy, Debug)]
pub struct Pollu {
    /// The twenty concentrations.
    #[state]
    pub y: [f64; 20],
}

#[system]
impl Pollu {
    fn derivative(&self) -> PolluState {
        let y = self.y;
        let r1 = 0.35 * y[0];
        let r2 = 26.6 * y[1] * y[3];
        let r3 = 12300.0 * y[4] * y[1];
        let r4 = 0.00086 * y[6];
        let r5 = 0.00082 * y[6];
        let r6 = 15000.0 * y[6] * y[5];
        let r7 = 0.00013 * y[8];
        let r8 = 24000.0 * y[8] * y[5];
        let r9 = 16500.0 * y[10] * y[1];
        let r10 = 9000.0 * y[10] * y[0];
        let r11 = 0.022 * y[12];
        let r12 = 12000.0 * y[9] * y[1];
        let r13 = 1.88 * y[13];
        let r14 = 16300.0 * y[0] * y[5];
        let r15 = 4800000.0 * y[2];
        let r16 = 0.00035 * y[3];
        let r17 = 0.0175 * y[3];
        let r18 = 100000000.0 * y[15];
        let r19 = 444000000000.0 * y[15];
        let r20 = 1240.0 * y[16] * y[5];
        let r21 = 2.1 * y[18];
        let r22 = 5.78 * y[18];
        let r23 = 0.0474 * y[0] * y[3];
        let r24 = 1780.0 * y[18] * y[0];
        let r25 = 3.12 * y[19];
        PolluState {
            y: [
                -r1 - r10 - r14 - r23 - r24 + r2 + r3 + r9 + r11 + r12 + r22 + r25,
                -r2 - r3 - r9 - r12 + r1 + r21,
                -r15 + r1 + r17 + r19 + r22,
                -r2 - r16 - r17 - r23 + r15,
                -r3 + r4 + r4 + r6 + r7 + r13 + r20,
                -r6 - r8 - r14 - r20 + r3 + r18 + r18,
                -r4 - r5 - r6 + r13,
                r4 + r5 + r6 + r7,
                -r7 - r8,
                -r12 + r7 + r9,
                -r9 - r10 + r8 + r11,
                r9,
                -r11 + r10,
                -r13 + r12,
                r14,
                -r18 - r19 + r16,
                -r20,
                r20,
                -r21 - r22 - r24 + r23 + r25,
                -r25 + r24,
            ],
        }
    }
}

/// van der Pol's oscillator, y₁′ = y₂, y₂′ = μ(1 − y₁²)y₂ − y₁ (stiff for large μ).
#[system(integrator = ImplicitEuler)]
#[derive(Clone, Copy, Debug)]
pub struct VanDerPol {
    /// Position-like variable y₁.
    #[state]
    pub y1: f64,
    /// Its rate y₂.
    #[state]
    pub y2: f64,
    /// Stiffness parameter μ.
    pub mu: f64,
}

#[system]
impl VanDerPol {
    fn derivative(&self) -> VanDerPolState {
        VanDerPolState {
            y1: self.y2,
            y2: self.mu * (1.0 - self.y1 * self.y1) * self.y2 - self.y1,
        }
    }
}
