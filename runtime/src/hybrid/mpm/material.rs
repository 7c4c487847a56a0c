//! The constitutive models of MPM: a weakly compressible fluid, fixed-corotated elasticity
//! (jelly), and snow (fixed corotated on the elastic part, with Stomakhin's plasticity and
//! hardening). Each gives the Kirchhoff stress τ = P·Fᵀ the grid's forces come from, the update
//! of the deformation a particle carries, and its strain energy.

use nalgebra::Matrix2;

use super::decompose::{rotation, svd};
use crate::math::Transcendental;
use crate::{Error, Result};

/// What a body is made of. Units are SI throughout (kg/m³, Pa); plane strain in 2-D.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Material {
    /// A weakly compressible fluid.
    Fluid(Fluid),
    /// An elastic solid (jelly).
    Elastic(Elastic),
    /// Snow: elastic until compressed or stretched past its critical strains, then plastic.
    Snow(Snow),
}

/// A weakly compressible fluid: the particle tracks only its volume ratio J (J ← J·(1 + Δt·tr C)
/// a step) and its Kirchhoff stress is τ = K·(J − 1)·I, the pressure of the 88-line MLS-MPM
/// program (`mpm88`, Hu et al. 2018), with strain energy Ψ(J) = K·(J − 1 − ln J) per unit
/// reference volume. There is no shear stress: the fluid is inviscid, and its sound speed
/// √(K/ρ) sets the stable step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fluid {
    /// Density ρ at rest (kg/m³; default 1000, water).
    pub density: f64,
    /// Bulk modulus K (Pa; default 4·10⁵: a sound speed of 20 m/s, `mpm88`'s E = 400 at unit
    /// density scaled to water's; water's own 2.2·10⁹ would need steps 74 times shorter).
    pub bulk_modulus: f64,
}

impl Default for Fluid {
    fn default() -> Self {
        Fluid {
            density: 1000.0,
            bulk_modulus: 4e5,
        }
    }
}

/// Fixed-corotated elasticity (Stomakhin, Howes, Schroeder & Teran 2012): strain energy
/// Ψ = μ·‖F − R‖² + λ/2·(J − 1)² per unit reference volume, R the rotation of F's polar
/// decomposition, so τ = 2μ·(F − R)·Fᵀ + λ·(J − 1)·J·I. It is rotation invariant (τ is
/// symmetric, so a body's angular momentum is kept) and, for small strains, linear elasticity
/// with Lamé parameters μ = E/(2(1 + ν)) and λ = Eν/((1 + ν)(1 − 2ν)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Elastic {
    /// Density ρ (kg/m³; default 1000).
    pub density: f64,
    /// Young's modulus E (Pa; default 3·10⁵: the MLS-MPM paper's 99-line program's jelly,
    /// E = 10³ softened by 0.3 at unit density, scaled to ρ = 1000).
    pub youngs_modulus: f64,
    /// Poisson's ratio ν in [0, ½) (default 0.2).
    pub poisson_ratio: f64,
}

impl Default for Elastic {
    fn default() -> Self {
        Elastic {
            density: 1000.0,
            youngs_modulus: 3e5,
            poisson_ratio: 0.2,
        }
    }
}

/// Snow after Stomakhin, Schroeder, Chai, Teran & Selle, "A Material Point Method for Snow
/// Simulation" (SIGGRAPH 2013): F = F_E·F_P. Fixed-corotated elasticity on F_E with Lamé
/// parameters hardened by e^{ξ(1 − J_P)}; after each step the singular values of F_E are clamped
/// to [1 − θ_c, 1 + θ_s] and what the clamp removes goes into F_P (only J_P = det F_P is kept).
/// Compacted snow (J_P < 1) is stiffer; stretched snow softer. Defaults: the paper's reference
/// snow (its Table 2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Snow {
    /// Density ρ (kg/m³; default 400).
    pub density: f64,
    /// Young's modulus E₀ of uncompacted snow (Pa; default 1.4·10⁵).
    pub youngs_modulus: f64,
    /// Poisson's ratio ν in [0, ½) (default 0.2).
    pub poisson_ratio: f64,
    /// Hardening coefficient ξ ≥ 0 (default 10).
    pub hardening: f64,
    /// Critical compression θ_c in [0, 1) (default 2.5·10⁻²).
    pub critical_compression: f64,
    /// Critical stretch θ_s ≥ 0 (default 7.5·10⁻³).
    pub critical_stretch: f64,
}

impl Default for Snow {
    fn default() -> Self {
        Snow {
            density: 400.0,
            youngs_modulus: 1.4e5,
            poisson_ratio: 0.2,
            hardening: 10.0,
            critical_compression: 2.5e-2,
            critical_stretch: 7.5e-3,
        }
    }
}

/// A material with its Lamé parameters worked out, as the particles' steps use it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Model {
    Fluid {
        k: f64,
    },
    Elastic {
        mu: f64,
        lambda: f64,
    },
    Snow {
        mu: f64,
        lambda: f64,
        xi: f64,
        low: f64,
        high: f64,
    },
}

/// Lamé parameters (μ, λ) of Young's modulus and Poisson's ratio.
fn lame(e: f64, nu: f64) -> (f64, f64) {
    (
        e / (2.0 * (1.0 + nu)),
        e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
    )
}

impl Material {
    /// Its density.
    pub fn density(&self) -> f64 {
        match self {
            Material::Fluid(m) => m.density,
            Material::Elastic(m) => m.density,
            Material::Snow(m) => m.density,
        }
    }

    /// The checked model.
    ///
    /// Errors: [`Error::InvalidInput`] for a density or modulus that is not finite and positive
    /// (a Young's modulus may be 0), a Poisson's ratio outside [0, ½), a negative or non-finite
    /// hardening, a critical compression outside [0, 1) or a negative or non-finite critical
    /// stretch.
    pub(crate) fn model(&self) -> Result<Model> {
        let positive = |name: &str, x: f64| {
            if x.is_finite() && x > 0.0 {
                Ok(())
            } else {
                Err(Error::invalid(
                    format!("material {name}"),
                    format!("must be finite and positive, got {x:?}"),
                ))
            }
        };
        let at_least_zero = |name: &str, x: f64, below: f64| {
            if x.is_finite() && x >= 0.0 && x < below {
                Ok(())
            } else {
                Err(Error::invalid(
                    format!("material {name}"),
                    format!("must be in [0, {below}), got {x:?}"),
                ))
            }
        };
        positive("density", self.density())?;
        match *self {
            Material::Fluid(m) => {
                positive("bulk_modulus", m.bulk_modulus)?;
                Ok(Model::Fluid { k: m.bulk_modulus })
            }
            Material::Elastic(m) => {
                at_least_zero("youngs_modulus", m.youngs_modulus, f64::INFINITY)?;
                at_least_zero("poisson_ratio", m.poisson_ratio, 0.5)?;
                let (mu, lambda) = lame(m.youngs_modulus, m.poisson_ratio);
                Ok(Model::Elastic { mu, lambda })
            }
            Material::Snow(m) => {
                at_least_zero("youngs_modulus", m.youngs_modulus, f64::INFINITY)?;
                at_least_zero("poisson_ratio", m.poisson_ratio, 0.5)?;
                at_least_zero("hardening", m.hardening, f64::INFINITY)?;
                at_least_zero("critical_compression", m.critical_compression, 1.0)?;
                at_least_zero("critical_stretch", m.critical_stretch, f64::INFINITY)?;
                let (mu, lambda) = lame(m.youngs_modulus, m.poisson_ratio);
                Ok(Model::Snow {
                    mu,
                    lambda,
                    xi: m.hardening,
                    low: 1.0 - m.critical_compression,
                    high: 1.0 + m.critical_stretch,
                })
            }
        }
    }
}

/// τ = 2μ·(F − R)·Fᵀ + λ·(J − 1)·J·I as (τ_xx, τ_xy, τ_yy).
#[inline]
fn corotated(f: &Matrix2<f64>, mu: f64, lambda: f64) -> [f64; 3] {
    let r = rotation(f);
    let j = f.determinant();
    let t = 2.0 * mu * (f - r) * f.transpose();
    let p = lambda * (j - 1.0) * j;
    [t[(0, 0)] + p, 0.5 * (t[(0, 1)] + t[(1, 0)]), t[(1, 1)] + p]
}

impl Model {
    /// The Kirchhoff stress (τ_xx, τ_xy, τ_yy) of a particle with deformation `f` and volume
    /// ratio `j` (the fluid's J, snow's J_P).
    #[inline]
    pub(crate) fn kirchhoff(&self, f: &Matrix2<f64>, j: f64) -> [f64; 3] {
        match *self {
            Model::Fluid { k } => {
                let p = k * (j - 1.0);
                [p, 0.0, p]
            }
            Model::Elastic { mu, lambda } => corotated(f, mu, lambda),
            Model::Snow { mu, lambda, xi, .. } => {
                let hard = Transcendental::exp(xi * (1.0 - j));
                corotated(f, mu * hard, lambda * hard)
            }
        }
    }

    /// Advances a particle's deformation by a step of `dt` with velocity gradient `c`:
    /// J ← J·(1 + dt·tr C) for a fluid, F ← (I + dt·C)·F for a solid, then snow's return to
    /// its elastic limits (the clamped part of F going into J_P).
    #[inline]
    pub(crate) fn deform(&self, f: &mut Matrix2<f64>, j: &mut f64, c: &Matrix2<f64>, dt: f64) {
        match *self {
            Model::Fluid { .. } => *j *= 1.0 + dt * c.trace(),
            Model::Elastic { .. } => *f = (Matrix2::identity() + dt * c) * *f,
            Model::Snow { low, high, .. } => {
                let trial = (Matrix2::identity() + dt * c) * *f;
                let (u, sigma, v) = svd(&trial);
                let clamped = [sigma[0].clamp(low, high), sigma[1].clamp(low, high)];
                if clamped != sigma {
                    *j *= sigma[0] / clamped[0] * (sigma[1] / clamped[1]);
                    *f = u * Matrix2::from_diagonal(&clamped.into()) * v.transpose();
                } else {
                    *f = trial;
                }
            }
        }
    }

    /// Strain energy per unit reference volume.
    pub(crate) fn energy(&self, f: &Matrix2<f64>, j: f64) -> f64 {
        let corotated = |mu: f64, lambda: f64| {
            let je = f.determinant();
            mu * (f - rotation(f)).norm_squared() + 0.5 * lambda * (je - 1.0) * (je - 1.0)
        };
        match *self {
            Model::Fluid { k } => k * (j - 1.0 - Transcendental::ln(j)),
            Model::Elastic { mu, lambda } => corotated(mu, lambda),
            Model::Snow { mu, lambda, xi, .. } => {
                let hard = Transcendental::exp(xi * (1.0 - j));
                corotated(mu * hard, lambda * hard)
            }
        }
    }

    /// The fastest elastic wave at the particle: √(K/ρ) for a fluid (at J = 1), the P-wave
    /// speed √((λ + 2μ)/ρ) for a solid, hardened for snow.
    pub(crate) fn wave_speed(&self, density: f64, j: f64) -> f64 {
        let stiffness = match *self {
            Model::Fluid { k } => k,
            Model::Elastic { mu, lambda } => lambda + 2.0 * mu,
            Model::Snow { mu, lambda, xi, .. } => {
                (lambda + 2.0 * mu) * Transcendental::exp(xi * (1.0 - j))
            }
        };
        (stiffness / density).sqrt()
    }

    /// Whether the model carries a deformation gradient (else only J).
    pub(crate) fn has_gradient(&self) -> bool {
        !matches!(self, Model::Fluid { .. })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// τ = P·Fᵀ with P = ∂Ψ/∂F: checked against central differences of the energy on a
    /// deformed, rotated F for the elastic model, and for the fluid τ = J·Ψ′(J)·I.
    #[test]
    fn stresses_are_the_derivatives_of_the_energies() {
        let elastic = Material::Elastic(Elastic::default()).model().unwrap();
        let (c, s) = (0.6f64, 0.8f64);
        let f = Matrix2::new(c, -s, s, c) * Matrix2::new(1.1, 0.05, 0.05, 0.93);
        let tau = elastic.kirchhoff(&f, 1.0);
        let h = 1e-6;
        let mut p = Matrix2::zeros();
        for a in 0..2 {
            for b in 0..2 {
                let mut up = f;
                let mut down = f;
                up[(a, b)] += h;
                down[(a, b)] -= h;
                p[(a, b)] = (elastic.energy(&up, 1.0) - elastic.energy(&down, 1.0)) / (2.0 * h);
            }
        }
        let expected = p * f.transpose();
        let scale = expected.abs().max();
        assert!((tau[0] - expected[(0, 0)]).abs() < 1e-6 * scale);
        assert!((tau[1] - expected[(0, 1)]).abs() < 1e-6 * scale);
        assert!((tau[1] - expected[(1, 0)]).abs() < 1e-6 * scale);
        assert!((tau[2] - expected[(1, 1)]).abs() < 1e-6 * scale);
        let fluid = Material::Fluid(Fluid::default()).model().unwrap();
        let j = 0.97;
        let derivative = (fluid.energy(&f, j + h) - fluid.energy(&f, j - h)) / (2.0 * h);
        let tau = fluid.kirchhoff(&f, j);
        assert!((tau[0] - j * derivative).abs() < 1e-6 * tau[0].abs());
    }

    /// Snow's return mapping: a compression past θ_c leaves F_E's singular values at 1 − θ_c
    /// and moves the rest into J_P, so det F_E·J_P is the total J.
    #[test]
    fn snow_clamps_its_elastic_strain_and_keeps_the_total_volume() {
        let snow = Material::Snow(Snow::default()).model().unwrap();
        let (mut f, mut jp) = (Matrix2::identity(), 1.0);
        let c = Matrix2::new(-1.0, 0.2, 0.0, -0.5);
        let dt: f64 = 0.1;
        let total = (Matrix2::<f64>::identity() + dt * c).determinant();
        snow.deform(&mut f, &mut jp, &c, dt);
        let (_, sigma, _) = svd(&f);
        assert!(sigma.iter().all(|&s| s >= 1.0 - 2.5e-2 - 1e-15));
        assert!((f.determinant() * jp - total).abs() < 1e-14);
        assert!(jp < 1.0);
    }

    #[test]
    fn bad_parameters_are_typed_errors() {
        let bad = [
            Material::Fluid(Fluid {
                density: 0.0,
                ..Fluid::default()
            }),
            Material::Fluid(Fluid {
                bulk_modulus: f64::NAN,
                ..Fluid::default()
            }),
            Material::Elastic(Elastic {
                poisson_ratio: 0.5,
                ..Elastic::default()
            }),
            Material::Snow(Snow {
                critical_compression: 1.0,
                ..Snow::default()
            }),
            Material::Snow(Snow {
                hardening: f64::INFINITY,
                ..Snow::default()
            }),
        ];
        for material in bad {
            assert!(matches!(material.model(), Err(Error::InvalidInput { .. })));
        }
    }
}
