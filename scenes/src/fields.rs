//! Field models: Gray–Scott reaction–diffusion.

use odyn::prelude::*;

/// Gray–Scott reaction–diffusion (Pearson, *Complex Patterns in a Simple System*, Science 261,
/// 1993): u′ = D_u∇²u − uv² + F(1 − u), v′ = D_v∇²v + uv² − (F + k)v on a grid of cell size dx.
#[system(integrator = ExplicitEuler, dt = 1.0)]
#[derive(Clone, Debug)]
pub struct GrayScott {
    /// The substrate u.
    #[field]
    pub u: Grid,
    /// The activator v.
    #[field]
    pub v: Grid,
    /// Diffusion rate of u.
    pub du: f64,
    /// Diffusion rate of v.
    pub dv: f64,
    /// Feed rate F.
    pub feed: f64,
    /// Kill rate k.
    pub kill: f64,
    /// Cell size.
    pub dx: f64,
}

#[system]
impl GrayScott {
    #[cell]
    fn reaction(&self, u: Stencil, v: Stencil) -> [f64; 2] {
        let uvv = u.c * v.c * v.c;
        let h2 = self.dx * self.dx;
        [
            self.du * u.laplacian() / h2 - uvv + self.feed * (1.0 - u.c),
            self.dv * v.laplacian() / h2 + uvv - (self.feed + self.kill) * v.c,
        ]
    }
}

impl GrayScott {
    /// Named (F, k) points: "mitosis" and "coral" from Karl Sims' reaction–diffusion tutorial
    /// (karlsims.com/rd.html, whose grid and Laplacian give nearly Pearson's D_u/dx² = 0.21),
    /// and "loops" from Munafo's Gray–Scott glossary (mrob.com/pub/comp/xmorphia, "Hilbert
    /// loop").
    pub const PATTERNS: [(&'static str, f64, f64); 3] = [
        ("mitosis", 0.0367, 0.0649),
        ("coral", 0.0545, 0.062),
        ("loops", 0.062, 0.063),
    ];

    /// Pearson's set-up on an n × n periodic grid of side 2.5: D_u = 2·10⁻⁵, D_v = 10⁻⁵, u = 1
    /// and v = 0 but for a central square of side 20/256 of the grid, where u = 1/2, v = 1/4.
    pub fn pearson(n: usize, feed: f64, kill: f64) -> odyn::Result<Self> {
        let inside = |i: usize, j: usize| {
            let r = n * 10 / 256;
            (n / 2 - r..n / 2 + r).contains(&i) && (n / 2 - r..n / 2 + r).contains(&j)
        };
        let grid = |value: &dyn Fn(bool) -> f64| {
            Grid::from_fn(n, n, Boundary::Periodic, |i, j| value(inside(i, j)))
        };
        Ok(GrayScott {
            u: grid(&|inside| if inside { 0.5 } else { 1.0 })?,
            v: grid(&|inside| if inside { 0.25 } else { 0.0 })?,
            du: 2e-5,
            dv: 1e-5,
            feed,
            kill,
            dx: 2.5 / n as f64,
        })
    }
}
