//! A rope of rigid rods as a differential–algebraic field model: the rod forces are algebraic
//! components, so the rope keeps its length to the tolerance instead of stretching like springs
//! or like a position-based solver's links.
//!
//! Particle i of the rope is cell i of an n × 1 grid. Rod i joins particle i − 1 to particle i
//! with length L; particle −1 is the pinned end at the origin, which is what every field's
//! `Boundary::Dirichlet(0.0)` reads west of cell 0 (its position, velocity and acceleration all
//! zero), and east of the last cell the rod force reads 0: no rod there. Per particle the state
//! has its position (x, y) and velocity (u, v), differential, and its acceleration (aₓ, a_y) and
//! the force per unit length λ of the rod above it, algebraic:
//!
//! ```text
//! x′ = u,   y′ = v,   u′ = aₓ,   v′ = a_y,
//! 0 = m·a − (λᵢ₊₁·(xᵢ₊₁ − xᵢ) − λᵢ·(xᵢ − xᵢ₋₁)) + m·g·ŷ,
//! 0 = dᵢ·(aᵢ − aᵢ₋₁) + |uᵢ − uᵢ₋₁|² + 2α·dᵢ·(uᵢ − uᵢ₋₁) + β²·(|dᵢ|² − L²)/2,
//! ```
//!
//! dᵢ = xᵢ − xᵢ₋₁. The last row is the rod's length constraint |dᵢ|² = L² differentiated twice
//! (index 1: the accelerations and rod forces follow from the positions and velocities), with
//! Baumgarte's drift terms (Comput. Methods Appl. Mech. Eng. 1, 1972), as in
//! [`crate::CartesianPendulum`]: on the exact solution they vanish. Every row reads the cell and
//! its east and west neighbours, so the Jacobian is block tridiagonal and the implicit methods
//! solve it by sparse LU. With one rod the rope is the Cartesian pendulum, λ included.

use odyn::grid::{Boundary, Grid, Stencil};
use odyn::prelude::*;

/// A rope of rigid rods hanging from the origin: see the [module](self).
#[system]
#[derive(Clone, Debug)]
pub struct RodRope {
    /// Horizontal positions (m).
    #[field]
    pub x: Grid,
    /// Vertical positions (m), up.
    #[field]
    pub y: Grid,
    /// Horizontal velocities (m/s).
    #[field]
    pub u: Grid,
    /// Vertical velocities (m/s).
    #[field]
    pub v: Grid,
    /// Horizontal accelerations (m/s²).
    #[field]
    #[algebraic]
    pub ax: Grid,
    /// Vertical accelerations (m/s²).
    #[field]
    #[algebraic]
    pub ay: Grid,
    /// The force per unit length of the rod above each particle (N/m), positive in tension.
    #[field]
    #[algebraic]
    pub lambda: Grid,
    /// Mass of each particle (kg).
    pub mass: f64,
    /// Rod length (m).
    pub length: f64,
    /// Gravity (m/s²).
    pub g: f64,
    /// Baumgarte's α (1/s).
    pub alpha: f64,
    /// Baumgarte's β (1/s).
    pub beta: f64,
}

#[system]
impl RodRope {
    #[cell]
    #[allow(clippy::too_many_arguments)]
    fn rods(
        &self,
        x: Stencil,
        y: Stencil,
        u: Stencil,
        v: Stencil,
        ax: Stencil,
        ay: Stencil,
        lambda: Stencil,
    ) -> [f64; 7] {
        let m = self.mass;
        // The rod above (from the west neighbour) and the rod below (to the east one).
        let (dx, dy) = (x.c - x.w, y.c - y.w);
        let (ex, ey) = (x.e - x.c, y.e - y.c);
        let (du, dv) = (u.c - u.w, v.c - v.w);
        let fx = lambda.e * ex - lambda.c * dx;
        let fy = lambda.e * ey - lambda.c * dy;
        let acceleration = dx * (ax.c - ax.w) + dy * (ay.c - ay.w) + du * du + dv * dv;
        let velocity = dx * du + dy * dv;
        let position = 0.5 * (dx * dx + dy * dy - self.length * self.length);
        [
            u.c,
            v.c,
            ax.c,
            ay.c,
            m * ax.c - fx,
            m * ay.c - fy + m * self.g,
            m * (acceleration + 2.0 * self.alpha * velocity + self.beta * self.beta * position),
        ]
    }
}

impl RodRope {
    /// A rope whose free particles start at `points` (m) at rest, each `mass` kg, its rods
    /// `length` m, under g = 9.81 m/s², with Baumgarte's gains α = β = 10/s; the accelerations
    /// and rod forces start at 0 for the consistent start to repair.
    ///
    /// Errors: from [`Grid::new`] (no points, or a value that is not finite).
    pub fn at_rest(points: &[[f64; 2]], mass: f64, length: f64) -> odyn::Result<Self> {
        let n = points.len();
        let grid = |values: Vec<f64>| Grid::new(n, 1, Boundary::Dirichlet(0.0), values);
        let zeros = || grid(vec![0.0; n]);
        Ok(RodRope {
            x: grid(points.iter().map(|p| p[0]).collect())?,
            y: grid(points.iter().map(|p| p[1]).collect())?,
            u: zeros()?,
            v: zeros()?,
            ax: zeros()?,
            ay: zeros()?,
            lambda: zeros()?,
            mass,
            length,
            g: 9.81,
            alpha: 10.0,
            beta: 10.0,
        })
    }

    /// `links` rods of `length` m held out straight at `angle` rad from the downward vertical
    /// (π/2: horizontal, along +x), at rest, particles of `mass` kg.
    ///
    /// Errors: from [`Grid::new`] when `links` is 0 or `angle` is not finite.
    pub fn straight(links: usize, mass: f64, length: f64, angle: f64) -> odyn::Result<Self> {
        let (sin, cos) = angle.sin_cos();
        let points: Vec<[f64; 2]> = (1..=links)
            .map(|i| {
                let s = i as f64 * length;
                [s * sin, -s * cos]
            })
            .collect();
        RodRope::at_rest(&points, mass, length)
    }

    /// The largest |(|dᵢ| − L)/L| of `state`'s rods: how far the rope has drifted off its
    /// length.
    pub fn drift(&self, state: &RodRopeState) -> f64 {
        let (x, y) = (state.field(0), state.field(1));
        (0..x.len())
            .map(|i| {
                let (px, py) = if i == 0 {
                    (0.0, 0.0)
                } else {
                    (x[i - 1], y[i - 1])
                };
                ((x[i] - px).hypot(y[i] - py) / self.length - 1.0).abs()
            })
            .fold(0.0, f64::max)
    }

    /// The rope's energy at `state` (J): kinetic plus gravitational, y = 0 at the pinned end.
    pub fn energy(&self, state: &RodRopeState) -> f64 {
        let (y, u, v) = (state.field(1), state.field(2), state.field(3));
        (0..y.len())
            .map(|i| self.mass * (0.5 * (u[i] * u[i] + v[i] * v[i]) + self.g * y[i]))
            .sum()
    }
}
