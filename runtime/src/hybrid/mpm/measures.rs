//! What an MPM run is checked by: its energies, momenta and volume, summed over the particles
//! in index order (the same bits on any thread count).

use nalgebra::Vector2;

use super::Mpm;
use crate::hybrid::transfer::Transfer;

impl Mpm {
    /// Kinetic energy Σ ½mₚ|vₚ|² (J per metre of depth), and under APIC the affine motion's
    /// ½mₚ·(h²/4)·‖Cₚ‖² too: the particle stands for the velocity field vₚ + Cₚ(x − xₚ) over its
    /// B-spline, whose second moment is h²/4 (Jiang et al. 2015, §5.3).
    pub fn kinetic_energy(&self) -> f64 {
        let h = self.options.cell;
        let affine = if self.options.transfer == Transfer::Apic {
            0.25 * h * h
        } else {
            0.0
        };
        // Zipped, not indexed, here and below: `x` and `v` are public and may have been resized
        // (`step` refuses that); a measure then covers the particles both lists still have.
        (self.mass.iter().zip(&self.v).zip(&self.c))
            .map(|((m, v), c)| {
                let c = if affine > 0.0 {
                    affine * c.norm_squared()
                } else {
                    0.0
                };
                0.5 * m * (v.norm_squared() + c)
            })
            .sum()
    }

    /// Gravitational potential energy −Σ mₚ·g·xₚ (zero at the origin).
    pub fn potential_energy(&self) -> f64 {
        let g = self.options.gravity;
        -self
            .mass
            .iter()
            .zip(&self.x)
            .map(|(m, x)| m * g.dot(x))
            .sum::<f64>()
    }

    /// Strain energy Σ Vₚ⁰·Ψ(Fₚ) of the materials' models ([`super::Material`]).
    pub fn strain_energy(&self) -> f64 {
        (0..self.mass.len())
            .map(|p| {
                let model = &self.materials[self.material[p] as usize].1;
                self.volume[p] * model.energy(&self.f[p], self.j[p])
            })
            .sum()
    }

    /// Total energy: kinetic, gravitational and strain.
    pub fn energy(&self) -> f64 {
        self.kinetic_energy() + self.potential_energy() + self.strain_energy()
    }

    /// Linear momentum Σ mₚvₚ (the affine velocities carry none).
    pub fn momentum(&self) -> Vector2<f64> {
        self.mass
            .iter()
            .zip(&self.v)
            .fold(Vector2::zeros(), |sum, (&m, v)| sum + m * v)
    }

    /// Angular momentum about `point`: Σ mₚ·(xₚ − point) × vₚ, and under APIC each particle's
    /// spin mₚ·(h²/4)·(C₁₀ − C₀₁) (the APIC paper's L, §5.3).
    pub fn angular_momentum(&self, point: Vector2<f64>) -> f64 {
        let h = self.options.cell;
        let spin = if self.options.transfer == Transfer::Apic {
            0.25 * h * h
        } else {
            0.0
        };
        (self.mass.iter().zip(&self.x).zip(&self.v).zip(&self.c))
            .map(|(((m, x), v), c)| {
                let r = x - point;
                m * (r.x * v.y - r.y * v.x + spin * (c[(1, 0)] - c[(0, 1)]))
            })
            .sum()
    }

    /// The particles' volume now, Σ Vₚ⁰·J (J = det F of a solid, the fluid's J, det F_E·J_P of
    /// snow): the area the material fills (m²).
    pub fn volume(&self) -> f64 {
        (0..self.mass.len())
            .map(|p| {
                let model = &self.materials[self.material[p] as usize].1;
                let j = if model.has_gradient() {
                    self.f[p].determinant() * self.j[p]
                } else {
                    self.j[p]
                };
                self.volume[p] * j
            })
            .sum()
    }

    /// The total mass (constant: particles are never made or lost).
    pub fn mass(&self) -> f64 {
        self.mass.iter().sum()
    }
}
