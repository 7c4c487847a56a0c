//! The SPH dam break of Martin & Moyce (1952).

use odyn::sph::{Sph, SphOptions};

/// A water column `a` wide and 2a high (n² = 2 in Martin & Moyce's notation) in a box 5a wide
/// and 2a high, `resolution` particles across a, the sound speed ten times the fastest flow
/// √(2g·2a) (weakly compressible SPH's rule: density varies ~1 %).
pub fn dam_break(a: f64, resolution: usize) -> odyn::Result<Sph> {
    let g = 9.81;
    Sph::block(
        SphOptions {
            spacing: a / resolution as f64,
            sound_speed: 10.0 * (2.0 * g * 2.0 * a).sqrt(),
            domain: (5.0 * a, 2.0 * a),
            ..SphOptions::default()
        },
        a,
        2.0 * a,
    )
}
