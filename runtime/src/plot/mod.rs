//! Charts as PNG or SVG, drawn with plotters and a bundled font (no system fonts needed): energy
//! against time, general line/marker charts, and to-scale views of particle scenes.

mod axes;
mod draw;
mod field;

pub use field::{Field, FieldStyle, field_animation, field_image};
mod chart;
mod energy;
mod particles;
mod scene;
#[cfg(test)]
mod tests;

pub use chart::{Chart, Series, Style};
pub use energy::{EnergyPlot, energy, energy_with};
pub use particles::{Particles, particle_animation, particles};
pub use scene::{Frame, View, animation, views};
