//! The constraints and colliders, and how a sweep projects the particles onto them.

use nalgebra::SVector;

use super::Xpbd;

/// One constraint between particles.
#[derive(Clone, Debug, PartialEq)]
pub enum Constraint<const D: usize> {
    /// |x_b − x_a| = `rest`, with compliance `compliance` (m/N; 0 is inextensible).
    Distance {
        /// The two particles.
        ends: [usize; 2],
        /// Rest length.
        rest: f64,
        /// Compliance α = 1/stiffness.
        compliance: f64,
    },
    /// Bending resistance along a chain or a sheet: the distance between the two outer
    /// particles of a triple (a, middle, c) is held at `rest` with compliance `compliance`, the
    /// "skip-one" bending constraint of position-based cloth and ropes (Müller, Heidelberger,
    /// Hennix & Ratcliff, "Position Based Dynamics", VRIPHYS 2006, §4.2 discusses it against
    /// the dihedral form). The middle particle is named so a model's lists read naturally; it
    /// takes no part.
    Bending {
        /// (a, middle, c).
        particles: [usize; 3],
        /// Rest distance between a and c.
        rest: f64,
        /// Compliance α.
        compliance: f64,
    },
    /// Particle `particle` is held at `at` (a rigid attachment that can be moved between steps).
    Pin {
        /// The particle.
        particle: usize,
        /// Where it is held.
        at: SVector<f64, D>,
    },
}

/// A static obstacle the particles cannot enter.
#[derive(Clone, Debug, PartialEq)]
pub enum Collider<const D: usize> {
    /// The half-space n·x ≥ offset (n a unit normal): e.g. the ground y ≥ 0.
    Plane {
        /// Unit normal pointing out of the obstacle.
        normal: SVector<f64, D>,
        /// n·x on the surface.
        offset: f64,
    },
    /// A solid sphere (a disc in 2-D). A particle inside is moved to the nearest point of the
    /// surface; one exactly at the centre, which has no nearest point, is moved out towards
    /// where it was at the start of the substep, or along +y (+x in 1-D) if that was the centre
    /// too.
    Sphere {
        /// Centre.
        centre: SVector<f64, D>,
        /// Radius.
        radius: f64,
    },
}

impl<const D: usize> Xpbd<D> {
    /// One Gauss–Seidel sweep over the constraints.
    pub(super) fn solve_constraints(&mut self, h: f64) {
        let inv_h2 = 1.0 / (h * h);
        for (k, constraint) in self.constraints.iter().enumerate() {
            let (a, b, rest, compliance) = match *constraint {
                Constraint::Distance {
                    ends: [a, b],
                    rest,
                    compliance,
                } => (a, b, rest, compliance),
                Constraint::Bending {
                    particles: [a, _, c],
                    rest,
                    compliance,
                } => (a, c, rest, compliance),
                Constraint::Pin { particle, at } => {
                    self.x[particle] = at;
                    continue;
                }
            };
            let (wa, wb) = (self.inverse_mass[a], self.inverse_mass[b]);
            let d = self.x[b] - self.x[a];
            let length = d.norm();
            if wa + wb == 0.0 || length == 0.0 {
                continue;
            }
            let n = d / length;
            let c = length - rest;
            let alpha = compliance * inv_h2;
            let delta = (-c - alpha * self.lambda[k]) / (wa + wb + alpha);
            self.lambda[k] += delta;
            self.x[a] -= wa * delta * n;
            self.x[b] += wb * delta * n;
        }
    }

    /// Moves every particle inside a collider to its surface.
    pub(super) fn collide(&mut self) {
        for ((x, &w), previous) in self
            .x
            .iter_mut()
            .zip(&self.inverse_mass)
            .zip(&self.previous)
        {
            if w == 0.0 {
                continue;
            }
            for collider in &self.colliders {
                match collider {
                    Collider::Plane { normal, offset } => {
                        let depth = offset - normal.dot(x);
                        if depth > 0.0 {
                            *x += depth * normal;
                        }
                    }
                    Collider::Sphere { centre, radius } => {
                        let d = *x - centre;
                        let distance = d.norm();
                        if distance < *radius {
                            *x = centre + *radius * outwards(d, distance, previous - centre);
                        }
                    }
                }
            }
        }
    }
}

impl<const D: usize> Constraint<D> {
    /// The compliance α (0 for a pin, which is rigid).
    pub(super) fn compliance(&self) -> f64 {
        match *self {
            Constraint::Distance { compliance, .. } | Constraint::Bending { compliance, .. } => {
                compliance
            }
            Constraint::Pin { .. } => 0.0,
        }
    }
}

/// The unit vector from a sphere's centre through a particle inside it at offset `d`
/// (|d| = `distance`). At the centre no direction is nearest the surface, so it is the one
/// towards `before`, the particle's offset at the start of the substep, and +y (+x in 1-D)
/// when that is zero too.
fn outwards<const D: usize>(
    d: SVector<f64, D>,
    distance: f64,
    before: SVector<f64, D>,
) -> SVector<f64, D> {
    if distance > 0.0 {
        return d / distance;
    }
    let norm = before.norm();
    if norm > 0.0 {
        return before / norm;
    }
    let mut up = SVector::zeros();
    if D > 0 {
        up[D.min(2) - 1] = 1.0;
    }
    up
}
