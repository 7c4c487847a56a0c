//! The material point method's scenes: the 88-line program's, jelly, water and snow falling
//! together, a ringing elastic block, a spinning disc and a snow column.

use odyn::hybrid::Transfer;
use odyn::hybrid::mpm::{Elastic, Fluid, Material, Mpm, MpmOptions, Snow, Walls};
use odyn::nalgebra::Vector2;

/// The 88-line program's step at its 128² grid (s).
pub const MPM88_DT: f64 = 2e-4;

/// The 88-line program's fluid: unit density, Kirchhoff pressure 400·(J − 1).
pub const MPM88_FLUID: Fluid = Fluid {
    density: 1.0,
    bulk_modulus: 400.0,
};

/// The scene of `mpm88.py`, the 88-line MLS-MPM program that ships with Taichi (Hu et al.
/// 2018): `positions` (in [0.2, 0.6]² in the program) of its fluid, each a quarter of a cell's
/// volume, falling at 1 m/s in a unit box of `grid`² nodes with walls 3 nodes thick (its
/// `bound`), gravity 9.8 m/s², APIC transfers.
pub fn mpm88_from(positions: &[Vector2<f64>], grid: usize) -> odyn::Result<Mpm> {
    let h = 1.0 / grid as f64;
    let mut mpm = Mpm::new(MpmOptions {
        nx: grid,
        ny: grid,
        cell: h,
        gravity: Vector2::new(0.0, -9.8),
        ..MpmOptions::default()
    })?;
    let volume = (0.5 * h) * (0.5 * h);
    mpm.add_particles(Material::Fluid(MPM88_FLUID), positions, volume, |_| {
        Vector2::new(0.0, -1.0)
    })?;
    Ok(mpm)
}

/// [`mpm88_from`] with `particles` positions drawn uniformly from [0.2, 0.6]² (Knuth's MMIX
/// linear congruential generator, seed 1) and sorted by grid cell, row by row (the order a
/// block's lattice has; drawn order is spatially random, which costs odyn's scatter — see
/// [`Mpm::sort_particles`]), on a grid of 128·√(particles/8192) nodes a side (the program's
/// 128² at its 8192 particles: the same particles per cell at every size), and the step that
/// keeps the program's Courant number, [`MPM88_DT`]·128/grid.
pub fn mpm88(particles: usize) -> odyn::Result<(Mpm, f64)> {
    let grid = (128.0 * (particles as f64 / 8192.0).sqrt())
        .round()
        .max(8.0) as usize;
    let mut seed = 1u64;
    let mut draw = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let positions: Vec<Vector2<f64>> = (0..particles)
        .map(|_| Vector2::new(0.2 + 0.4 * draw(), 0.2 + 0.4 * draw()))
        .collect();
    let mut mpm = mpm88_from(&positions, grid)?;
    mpm.sort_particles()?;
    Ok((mpm, MPM88_DT * 128.0 / grid as f64))
}

/// Jelly, water and snow in a unit box of `grid`² nodes, after the MLS-MPM paper's 99-line
/// program: a block of water (0.3 m square) on the left, a jelly block and a snow block above the
/// middle and right, all dropped from rest; walls 3 nodes thick that the material slides along.
/// Returns the simulation and its stable step at rest, [`Mpm::stable_dt`].
pub fn jelly_water_snow(grid: usize) -> odyn::Result<(Mpm, f64)> {
    let mut mpm = Mpm::new(MpmOptions {
        nx: grid,
        ny: grid,
        cell: 1.0 / grid as f64,
        ..MpmOptions::default()
    })?;
    let rest = |_| Vector2::zeros();
    let v = Vector2::new;
    mpm.add_block(
        Material::Fluid(Fluid::default()),
        v(0.05, 0.05),
        v(0.35, 0.35),
        rest,
    )?;
    mpm.add_block(
        Material::Elastic(Elastic::default()),
        v(0.45, 0.45),
        v(0.65, 0.65),
        rest,
    )?;
    mpm.add_block(
        Material::Snow(Snow::default()),
        v(0.65, 0.1),
        v(0.9, 0.3),
        rest,
    )?;
    let dt = mpm.stable_dt();
    Ok((mpm, dt))
}

/// An elastic block L = 1 m square with `cells` cells across it, floating free (no gravity),
/// ringing in its first longitudinal mode: vₓ = V·cos(π(x − x₀)/L), V = 10⁻³·c, with
/// Poisson's ratio 0 (λ = 0), so the mode is an exact solution of plane-strain linear elasticity
/// whatever the block's height (σ_yy = σ_xy = 0 on its faces), of period T = 2L/c,
/// c = √(E/ρ) = 10 m/s: 0.2 s.
pub struct RingingBlock {
    /// The simulation.
    pub mpm: Mpm,
    /// The period of the continuum, 2L/c (s).
    pub period: f64,
    /// The step: 0.3·h/c.
    pub dt: f64,
    /// The particles of the block's left half, whose mean vₓ is ∝ cos(2πt/T).
    pub left: Vec<usize>,
}

/// [`RingingBlock`] with `cells` cells across the block.
pub fn ringing_block(cells: usize) -> odyn::Result<RingingBlock> {
    let (l, rho, e): (f64, f64, f64) = (1.0, 1000.0, 1e5);
    let c = (e / rho).sqrt();
    let h = l / cells as f64;
    let margin = 8.0 * h;
    let mut mpm = Mpm::new(MpmOptions {
        nx: cells + 16,
        ny: cells + 16,
        cell: h,
        gravity: Vector2::zeros(),
        ..MpmOptions::default()
    })?;
    let solid = Material::Elastic(Elastic {
        density: rho,
        youngs_modulus: e,
        poisson_ratio: 0.0,
    });
    let amplitude = 1e-3 * c;
    let corner = Vector2::new(margin, margin);
    let block = mpm.add_block(solid, corner, corner.add_scalar(l), |x| {
        Vector2::new(
            amplitude * (std::f64::consts::PI * (x.x - margin) / l).cos(),
            0.0,
        )
    })?;
    let left = block.filter(|&p| mpm.x[p].x < margin + 0.5 * l).collect();
    Ok(RingingBlock {
        mpm,
        period: 2.0 * l / c,
        dt: 0.3 * h / c,
        left,
    })
}

impl RingingBlock {
    /// The mean vₓ of the left half.
    pub fn signal(&self) -> f64 {
        self.left.iter().map(|&p| self.mpm.v[p].x).sum::<f64>() / self.left.len() as f64
    }

    /// Steps until the signal has crossed zero five times (two periods, from the first
    /// crossing to the fifth, each found by linear interpolation between steps) and returns
    /// the measured period.
    pub fn measure_period(&mut self) -> odyn::Result<f64> {
        let mut crossings = Vec::new();
        let (mut t, mut before) = (0.0, self.signal());
        while crossings.len() < 5 {
            self.mpm.step(self.dt)?;
            t += self.dt;
            let now = self.signal();
            if now.signum() != before.signum() {
                crossings.push(t - self.dt * now / (now - before));
            }
            before = now;
        }
        Ok((crossings[4] - crossings[0]) / 2.0)
    }
}

/// An elastic disc (radius 0.25 m, E = 10⁵ Pa, ν = 0.2, ρ = 1000 kg/m³) spinning freely at
/// 2 rad/s about the centre of a unit box of `grid`² nodes, no gravity, with `transfer`.
/// Returns the simulation and its centre.
pub fn spinning_disc(grid: usize, transfer: Transfer) -> odyn::Result<(Mpm, Vector2<f64>)> {
    let mut mpm = Mpm::new(MpmOptions {
        nx: grid,
        ny: grid,
        cell: 1.0 / grid as f64,
        gravity: Vector2::zeros(),
        transfer,
        ..MpmOptions::default()
    })?;
    let centre = Vector2::new(0.5, 0.5);
    let jelly = Material::Elastic(Elastic {
        density: 1000.0,
        youngs_modulus: 1e5,
        poisson_ratio: 0.2,
    });
    mpm.add_disc(jelly, centre, 0.25, |x| {
        let r = x - centre;
        2.0 * Vector2::new(-r.y, r.x)
    })?;
    Ok((mpm, centre))
}

/// A 0.5 m square column of `snow` standing on the floor of a 3 m × 1.5 m box at `cells` cells
/// a metre, sticky walls (the floor holds the snow as the ground would), from rest. Returns the
/// simulation and the height of the floor (the walls' inner edge, 3 cells up).
pub fn snow_column(snow: Snow, cells: usize) -> odyn::Result<(Mpm, f64)> {
    let h = 1.0 / cells as f64;
    let mut mpm = Mpm::new(MpmOptions {
        nx: 3 * cells,
        ny: 3 * cells / 2,
        cell: h,
        walls: Walls::Sticky,
        ..MpmOptions::default()
    })?;
    let floor = 3.0 * h;
    mpm.add_block(
        Material::Snow(snow),
        Vector2::new(1.25, floor),
        Vector2::new(1.75, floor + 0.5),
        |_| Vector2::zeros(),
    )?;
    Ok((mpm, floor))
}

/// The height of a snow column above `floor`: its highest particle, plus the half spacing the
/// block's sampling leaves below its top.
pub fn column_height(mpm: &Mpm, floor: f64) -> f64 {
    let half = 0.5 * mpm.options().cell / mpm.options().sampling as f64;
    mpm.x.iter().fold(f64::MIN, |m, x| m.max(x.y)) + half - floor
}

/// Martin & Moyce's dam break (`crate::fluids`) for MPM's weakly compressible water: a column
/// `a` wide and 2a high, `cells` cells across it (four particles a cell), in a room 5a wide and
/// 3a high inside walls 3 nodes thick (slip), the sound speed ten times the fastest flow
/// √(2g·2a) as for SPH (K = ρc²). The column stands in the room's lower left corner.
pub fn mpm_dam_break(a: f64, cells: usize) -> odyn::Result<Mpm> {
    let h = a / cells as f64;
    let mut mpm = Mpm::new(MpmOptions {
        nx: 5 * cells + 6,
        ny: 3 * cells + 6,
        cell: h,
        ..MpmOptions::default()
    })?;
    let c = 10.0 * (2.0 * 9.81 * 2.0 * a).sqrt();
    let water = Fluid {
        density: 1000.0,
        bulk_modulus: 1000.0 * c * c,
    };
    let corner = Vector2::new(3.0 * h, 3.0 * h);
    mpm.add_block(
        Material::Fluid(water),
        corner,
        corner + Vector2::new(a, 2.0 * a),
        |_| Vector2::zeros(),
    )?;
    Ok(mpm)
}

/// The surge front of [`mpm_dam_break`]: how far from the left wall (3 nodes in) the water runs
/// along the floor — the largest x of the particles within two particle spacings of the floor.
pub fn mpm_front(mpm: &Mpm) -> f64 {
    let h = mpm.options().cell;
    let wall = mpm.options().wall as f64 * h;
    let floor = wall + 2.0 * h / mpm.options().sampling as f64;
    mpm.x
        .iter()
        .filter(|x| x.y < floor)
        .fold(0.0, |m, x| m.max(x.x - wall))
}
