//! The Baraff–Witkin cloth: a square sheet of particles joined by structural, shear and bend
//! springs, pinned at its two top corners, under weight and air drag (Baraff & Witkin, *Large
//! Steps in Cloth Simulation*, SIGGRAPH 1998).

use odyn::particles::Spring;
use odyn::prelude::*;
use odyn::xpbd::{Constraint, Xpbd, XpbdOptions};

/// A cloth: damped springs between particles, weight and air drag on each.
#[system(integrator = ImplicitEuler, dt = 1.0 / 60.0)]
#[derive(Clone, Debug)]
pub struct Cloth {
    /// Particle positions (m).
    #[position]
    pub x: Vec<Vector3<f64>>,
    /// Particle velocities (m/s).
    #[velocity]
    pub v: Vec<Vector3<f64>>,
    /// Particle masses (kg).
    #[mass]
    pub mass: Vec<f64>,
    /// The two top corners.
    #[pinned]
    pub pinned: Vec<usize>,
    /// Structural, shear and bend springs.
    pub springs: Vec<Spring>,
    /// Gravitational acceleration (m/s²).
    pub gravity: Vector3<f64>,
    /// Linear air drag (N·s/m per particle).
    pub drag: f64,
}

#[system]
impl Cloth {
    /// Hooke's law along the spring plus damping of the relative velocity along it.
    #[pair(springs)]
    fn spring(
        &self,
        s: &Spring,
        xa: Vector3<f64>,
        xb: Vector3<f64>,
        va: Vector3<f64>,
        vb: Vector3<f64>,
    ) -> Vector3<f64> {
        let d = xb - xa;
        let length = d.norm();
        let direction = d / length;
        direction * (s.stiffness * (length - s.rest) + s.damping * (vb - va).dot(&direction))
    }

    /// Weight and linear air drag.
    #[particle]
    fn weight(&self, i: usize, _x: Vector3<f64>, v: Vector3<f64>) -> Vector3<f64> {
        self.gravity * self.mass[i] - v * self.drag
    }

    /// Spring energy ½k(|d| − L)² plus gravitational energy −m·g·x.
    pub fn potential(&self) -> f64 {
        let springs: f64 = self
            .springs
            .iter()
            .map(|s| 0.5 * s.stiffness * ((self.x[s.b] - self.x[s.a]).norm() - s.rest).powi(2))
            .sum();
        let gravity: f64 = self
            .x
            .iter()
            .zip(&self.mass)
            .map(|(x, m)| -m * self.gravity.dot(x))
            .sum();
        springs + gravity
    }
}

impl Cloth {
    /// The same cloth as XPBD particles: every spring a distance constraint of compliance
    /// 1/k, the same masses, pins and gravity (no air drag, no spring damping), `substeps`
    /// substeps of one sweep per step (`odyn::xpbd`).
    pub fn as_xpbd(&self, substeps: u32) -> odyn::Result<Xpbd<3>> {
        let mut particles = Xpbd::new(
            self.x.clone(),
            self.v.clone(),
            &self.mass,
            &self.pinned,
            self.gravity,
        )?;
        particles.constraints = self
            .springs
            .iter()
            .map(|s| Constraint::Distance {
                ends: [s.a, s.b],
                rest: s.rest,
                compliance: 1.0 / s.stiffness,
            })
            .collect();
        particles.options = XpbdOptions {
            substeps,
            iterations: 1,
        };
        Ok(particles)
    }
}

/// Where the sheet starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Hang {
    /// Horizontal, in the x–z plane at y = 0; row 0 (z = 0) is the pinned edge, so the sheet
    /// falls and swings down from it.
    Horizontal,
    /// Vertical, in the x–y plane, row 0 at y = 0 and the rest below it: the sheet hangs at rest
    /// but for its springs' sag.
    Vertical,
}

/// An n × n sheet of side 1 m: particle (i, j) is row i, column j; springs join each particle to
/// its neighbours along the rows and columns (structural), across each square (shear) and two
/// apart (bend), all at rest length; the two top corners, (0, 0) and (0, n − 1), are pinned.
#[derive(Clone, Copy, Debug)]
pub struct Sheet {
    /// Particles per side (at least 2).
    pub n: usize,
    /// Spring stiffness k (N/m).
    pub stiffness: f64,
    /// Spring damping along each spring (N·s/m).
    pub damping: f64,
    /// Mass of each particle (kg).
    pub particle_mass: f64,
    /// Linear air drag on each particle (N·s/m).
    pub particle_drag: f64,
    /// Where the sheet starts.
    pub hang: Hang,
}

impl Sheet {
    /// The cloth of the `cloth` example and the particle benches: 0.5 kg in all, drag 0.02 N·s/m
    /// in all, starting horizontal, k = 10⁴ N/m, undamped springs.
    pub fn falling(n: usize) -> Self {
        let particles = (n * n) as f64;
        Sheet {
            n,
            stiffness: 1e4,
            damping: 0.0,
            particle_mass: 0.5 / particles,
            particle_drag: 0.02 / particles,
            hang: Hang::Horizontal,
        }
    }

    /// The cloth and the indices of its structural springs (the ones worth drawing).
    pub fn build(&self) -> (Cloth, Vec<usize>) {
        let n = self.n;
        let spacing = 1.0 / (n - 1) as f64;
        let id = |i: usize, j: usize| i * n + j;
        let x: Vec<_> = (0..n * n)
            .map(|p| {
                let (along, down) = ((p % n) as f64 * spacing, (p / n) as f64 * spacing);
                match self.hang {
                    Hang::Horizontal => Vector3::new(along, 0.0, down),
                    Hang::Vertical => Vector3::new(along, -down, 0.0),
                }
            })
            .collect();
        let mut springs = Vec::new();
        let mut structural = Vec::new();
        let mut link = |a: usize, b: usize, drawn: bool| {
            if drawn {
                structural.push(springs.len());
            }
            springs.push(Spring::at_rest(&x, a, b, self.stiffness, self.damping));
        };
        for i in 0..n {
            for j in 0..n {
                if j + 1 < n {
                    link(id(i, j), id(i, j + 1), true);
                }
                if i + 1 < n {
                    link(id(i, j), id(i + 1, j), true);
                }
                if i + 1 < n && j + 1 < n {
                    link(id(i, j), id(i + 1, j + 1), false);
                    link(id(i, j + 1), id(i + 1, j), false);
                }
                if j + 2 < n {
                    link(id(i, j), id(i, j + 2), false);
                }
                if i + 2 < n {
                    link(id(i, j), id(i + 2, j), false);
                }
            }
        }
        let cloth = Cloth {
            v: vec![Vector3::zeros(); n * n],
            mass: vec![self.particle_mass; n * n],
            pinned: vec![id(0, 0), id(0, n - 1)],
            springs,
            gravity: Vector3::new(0.0, -9.81, 0.0),
            drag: self.particle_drag,
            x,
        };
        (cloth, structural)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An n × n sheet has 2n(n − 1) structural springs, 2(n − 1)² shear and 2n(n − 2) bend
    /// springs, all at rest, 0.5 kg in all for the falling cloth, and its two top corners pinned.
    #[test]
    fn a_sheet_has_the_springs_and_mass_of_its_topology() {
        for n in [2, 3, 7] {
            let (cloth, structural) = Sheet::falling(n).build();
            assert_eq!(structural.len(), 2 * n * (n - 1));
            let springs = 2 * n * (n - 1) + 2 * (n - 1) * (n - 1) + 2 * n * (n - 2);
            assert_eq!(cloth.springs.len(), springs);
            for s in &cloth.springs {
                let length = (cloth.x[s.b] - cloth.x[s.a]).norm();
                assert!((length - s.rest).abs() < 1e-15, "{length} vs {}", s.rest);
            }
            let mass: f64 = cloth.mass.iter().sum();
            assert!((mass - 0.5).abs() < 1e-14, "{mass}");
            assert_eq!(cloth.pinned, vec![0, n - 1]);
            assert!(cloth.potential().abs() < 1e-12, "flat, at rest, at y = 0");
        }
    }
}
