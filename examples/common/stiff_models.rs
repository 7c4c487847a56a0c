//! The four problems of the Bari stiff test set (Mazzia & Magherini, *Test Set for Initial Value
//! Problem Solvers*, release 2.4, 2008) as `#[system]` models, shared by the `stiff_suite` example
//! and the peer benches (`peers/benches/stiff.rs`), so both integrate the same equations.
#![allow(
    dead_code,
    reason = "each user of this file solves a different subset of the problems"
)]

use odyn::prelude::*;

/// A → B (0.04), B + C → A + C (10⁴), 2B → B + C (3·10⁷) (Robertson 1966).
#[system]
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
}

#[system]
impl Robertson {
    fn derivative(&self) -> RobertsonState {
        let slow = 0.04 * self.a;
        let exchange = 1e4 * self.b * self.c;
        let fast = 3e7 * self.b * self.b;
        RobertsonState {
            a: -slow + exchange,
            b: slow - exchange - fast,
            c: fast,
        }
    }
}

/// HIRES (Schäfer 1975; Hairer & Wanner, *Solving ODEs II*, §IV.10), as in the test set's
/// `hires.f`.
#[system]
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

/// van der Pol's oscillator, y₁′ = y₂, y₂′ = μ(1 − y₁²)y₂ − y₁.
#[system]
pub struct VanDerPol {
    /// Position.
    #[state]
    pub x: f64,
    /// Velocity.
    #[state]
    pub v: f64,
    /// Stiffness μ.
    pub mu: f64,
}

#[system]
impl VanDerPol {
    fn derivative(&self) -> VanDerPolState {
        VanDerPolState {
            x: self.v,
            v: self.mu * (1.0 - self.x * self.x) * self.v - self.x,
        }
    }
}
