//! The dam break of Martin & Moyce (1952), for SPH and for FLIP, and their measurements.

use odyn::hybrid::Transfer;
use odyn::hybrid::flip::{Flip, FlipOptions};
use odyn::nalgebra::Vector2;
use odyn::sph::{Sph, SphOptions};

/// Martin & Moyce's surge front for n² = 2, (T, Z) with Z = z/a and T = t·√(2g/a): J. C. Martin
/// & W. J. Moyce, "An experimental study of the collapse of liquid columns on a rigid horizontal
/// plane", Phil. Trans. R. Soc. Lond. A 244 (1952) 312, Table 2 (as tabulated in the Lethe
/// project's dam-break post-processing; the same data `examples/sph.rs` plots).
pub const MARTIN_MOYCE: [(f64, f64); 15] = [
    (0.41, 1.11),
    (0.84, 1.22),
    (1.19, 1.44),
    (1.43, 1.67),
    (1.63, 1.89),
    (1.83, 2.11),
    (1.98, 2.33),
    (2.20, 2.56),
    (2.32, 2.78),
    (2.51, 3.00),
    (2.65, 3.22),
    (2.83, 3.44),
    (2.98, 3.67),
    (3.11, 3.89),
    (3.33, 4.11),
];

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

/// The same column for FLIP: `cells` cells across a (four particles a cell), in a room 5a wide
/// and 3a high inside the walls (air above the column, so its top is a free surface), with
/// `transfer`. The column stands in the room's lower left corner, (h, h) to (h + a, h + 2a).
pub fn flip_dam_break(a: f64, cells: usize, transfer: Transfer) -> odyn::Result<Flip> {
    let h = a / cells as f64;
    let mut flip = Flip::new(FlipOptions {
        nx: 5 * cells + 2,
        ny: 3 * cells + 2,
        cell: h,
        transfer,
        ..FlipOptions::default()
    })?;
    let corner = Vector2::new(h, h);
    flip.add_block(corner, corner + Vector2::new(a, 2.0 * a), |_| {
        Vector2::zeros()
    })?;
    Ok(flip)
}
