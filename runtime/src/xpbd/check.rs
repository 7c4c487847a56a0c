//! What [`Xpbd`] refuses: its input before a step, and a step that left a value non-finite.

use super::{Collider, Constraint, Xpbd, XpbdOptions};
use crate::{Error, Result};

impl<const D: usize> Xpbd<D> {
    /// Checks the particles, constraints, colliders and options ([`Xpbd::step`] does, every
    /// step).
    ///
    /// Errors: [`Error::InvalidInput`] for position or velocity lists whose length changed, a
    /// position or velocity that is not finite (`x[i]`, `v[i]`), a non-finite gravity, a
    /// constraint on a particle that does not exist, a negative or non-finite compliance or
    /// rest length, a non-finite pin position, a plane whose normal is not a unit vector, a
    /// sphere with a non-positive radius, or substeps or iterations outside 1 to
    /// [`XpbdOptions::MAX`].
    pub fn check(&self) -> Result<()> {
        let n = self.inverse_mass.len();
        if self.x.len() != n || self.v.len() != n {
            return Err(Error::invalid(
                "particles",
                format!(
                    "{} positions and {} velocities for {n} particles; particles cannot be added \
                     or removed",
                    self.x.len(),
                    self.v.len()
                ),
            ));
        }
        for (name, list) in [("x", &self.x), ("v", &self.v)] {
            if let Some(i) = list.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
                return Err(Error::invalid(
                    format!("{name}[{i}]"),
                    format!(
                        "{:?} is not finite; write only finite values into `Xpbd::{name}`",
                        list[i].as_slice()
                    ),
                ));
            }
        }
        if !self.gravity.iter().all(|c| c.is_finite()) {
            return Err(Error::invalid(
                "gravity",
                format!("{:?} is not finite", self.gravity.as_slice()),
            ));
        }
        let exists = |i: usize, what: &str| {
            if i < n {
                Ok(())
            } else {
                Err(Error::invalid(
                    what.to_string(),
                    format!("particle {i} does not exist ({n} particles)"),
                ))
            }
        };
        let valid = |x: f64| x.is_finite() && x >= 0.0;
        for (k, c) in self.constraints.iter().enumerate() {
            let what = format!("constraints[{k}]");
            let (particles, rest, compliance): (&[usize], f64, f64) = match c {
                Constraint::Distance {
                    ends,
                    rest,
                    compliance,
                } => (ends, *rest, *compliance),
                Constraint::Bending {
                    particles,
                    rest,
                    compliance,
                } => (particles, *rest, *compliance),
                Constraint::Pin { particle, at } => {
                    if !at.iter().all(|c| c.is_finite()) {
                        return Err(Error::invalid(what, "the pin position must be finite"));
                    }
                    (std::slice::from_ref(particle), 0.0, 0.0)
                }
            };
            particles.iter().try_for_each(|&i| exists(i, &what))?;
            if !(valid(rest) && valid(compliance)) {
                return Err(Error::invalid(
                    what,
                    format!(
                        "rest length and compliance must be finite and ≥ 0, got {rest:?} and \
                         {compliance:?}"
                    ),
                ));
            }
        }
        for (k, c) in self.colliders.iter().enumerate() {
            let ok = match c {
                Collider::Plane { normal, offset } => {
                    (normal.norm() - 1.0).abs() < 1e-9 && offset.is_finite()
                }
                Collider::Sphere { centre, radius } => {
                    centre.iter().all(|c| c.is_finite()) && radius.is_finite() && *radius > 0.0
                }
            };
            if !ok {
                return Err(Error::invalid(
                    format!("colliders[{k}]"),
                    "a plane needs a unit normal and a finite offset; a sphere a finite centre \
                     and a positive radius",
                ));
            }
        }
        let XpbdOptions {
            substeps,
            iterations,
        } = self.options;
        let allowed = 1..=XpbdOptions::MAX;
        if !(allowed.contains(&substeps) && allowed.contains(&iterations)) {
            return Err(Error::invalid(
                "options",
                format!(
                    "substeps and iterations must be at least 1 and at most {}, got {substeps} \
                     and {iterations}",
                    XpbdOptions::MAX
                ),
            ));
        }
        Ok(())
    }

    /// [`Error::NotFinite`] if the step just taken left a position or velocity non-finite.
    pub(super) fn check_finite(&self, dt: f64) -> Result<()> {
        for (name, list) in [("x", &self.x), ("v", &self.v)] {
            if let Some((i, value)) = list
                .iter()
                .enumerate()
                .find_map(|(i, p)| p.iter().find(|c| !c.is_finite()).map(|c| (i, *c)))
            {
                return Err(Error::NotFinite {
                    solver: "Xpbd",
                    step: self.steps,
                    t: self.t,
                    dt,
                    component: format!("{name}[{i}]"),
                    value,
                    advice: "reduce dt, or check that rest lengths, pin positions and \
                             gravity are of the scene's size",
                });
            }
        }
        Ok(())
    }
}
