//! One MLS-MPM substep of the 88-line program's scene (`scenes::hybrid::mpm88`: a weakly
//! compressible fluid block dropped in a unit box) at 8 192, 32 768 and 131 072 particles
//! (grids of 128², 256², 512²), after 100 substeps: odyn's `Mpm::step` on one and two rayon
//! threads, beside `hand`, the same algorithm as a plain serial loop written here (the program
//! transliterated: arrays of particles, a column-major grid, nothing shared with odyn).
//! `cargo bench --bench mpm`. `scripts/taichi_mpm88.py` times Taichi on the same scene.

use odyn::hybrid::mpm::Mpm;
use scenes::hybrid::mpm88;

fn main() {
    divan::main();
}

const SIZES: [usize; 3] = [8192, 32768, 131072];

/// The scene after 100 substeps, and its step.
fn scene(particles: usize) -> (Mpm, f64) {
    let (mut mpm, dt) = mpm88(particles).expect("the 88-line scene");
    for _ in 0..100 {
        mpm.step(dt).expect("a stable substep");
    }
    (mpm, dt)
}

fn odyn(bencher: divan::Bencher, particles: usize, threads: usize) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    let (mut mpm, dt) = scene(particles);
    // The step runs inside the pool (one hand-over a substep, timed with it), as a program
    // whose whole loop runs there would.
    bencher.bench_local(|| pool.install(|| mpm.step(dt).expect("a stable substep")));
}

#[divan::bench(args = SIZES)]
fn odyn_1_thread(bencher: divan::Bencher, particles: usize) {
    odyn(bencher, particles, 1);
}

#[divan::bench(args = SIZES)]
fn odyn_2_threads(bencher: divan::Bencher, particles: usize) {
    odyn(bencher, particles, 2);
}

#[divan::bench(args = SIZES)]
fn hand(bencher: divan::Bencher, particles: usize) {
    let (start, dt) = mpm88(particles).expect("the 88-line scene");
    let n = start.options().nx;
    let mut hand = Hand {
        x: start.x.iter().map(|x| [x.x, x.y]).collect(),
        v: vec![[0.0, -1.0]; particles],
        c: vec![[0.0; 4]; particles],
        j: vec![1.0; particles],
        grid_v: vec![[0.0; 2]; n * n],
        grid_m: vec![0.0; n * n],
        n,
    };
    for _ in 0..100 {
        hand.substep(dt);
    }
    bencher.bench_local(|| hand.substep(dt));
}

/// `mpm88.py`'s state: particles' x, v, C, J; the grid's velocity and mass, node (i, j) at
/// i·n + j as Taichi lays out a 2-D field.
struct Hand {
    x: Vec<[f64; 2]>,
    v: Vec<[f64; 2]>,
    c: Vec<[f64; 4]>,
    j: Vec<f64>,
    grid_v: Vec<[f64; 2]>,
    grid_m: Vec<f64>,
    n: usize,
}

impl Hand {
    /// `substep()` of `mpm88.py`, line by line.
    fn substep(&mut self, dt: f64) {
        let n = self.n;
        let (dx, inv_dx) = (1.0 / n as f64, n as f64);
        let p_vol = (dx * 0.5) * (dx * 0.5);
        let p_mass = p_vol;
        let (e, gravity, bound) = (400.0, 9.8, 3);
        self.grid_v.fill([0.0; 2]);
        self.grid_m.fill(0.0);
        for p in 0..self.x.len() {
            let (base, fx, w) = stencil(self.x[p], inv_dx);
            let stress = -dt * 4.0 * e * p_vol * (self.j[p] - 1.0) * inv_dx * inv_dx;
            let c = self.c[p];
            let affine = [
                stress + p_mass * c[0],
                p_mass * c[1],
                p_mass * c[2],
                stress + p_mass * c[3],
            ];
            let v = self.v[p];
            for i in 0..3 {
                for j in 0..3 {
                    let dpos = [(i as f64 - fx[0]) * dx, (j as f64 - fx[1]) * dx];
                    let weight = w[0][i] * w[1][j];
                    let k = (base[0] + i) * n + base[1] + j;
                    self.grid_v[k][0] +=
                        weight * (p_mass * v[0] + affine[0] * dpos[0] + affine[1] * dpos[1]);
                    self.grid_v[k][1] +=
                        weight * (p_mass * v[1] + affine[2] * dpos[0] + affine[3] * dpos[1]);
                    self.grid_m[k] += weight * p_mass;
                }
            }
        }
        for i in 0..n {
            for j in 0..n {
                let k = i * n + j;
                let m = self.grid_m[k];
                let g = &mut self.grid_v[k];
                if m > 0.0 {
                    g[0] /= m;
                    g[1] /= m;
                }
                g[1] -= dt * gravity;
                if (i < bound && g[0] < 0.0) || (i > n - bound && g[0] > 0.0) {
                    g[0] = 0.0;
                }
                if (j < bound && g[1] < 0.0) || (j > n - bound && g[1] > 0.0) {
                    g[1] = 0.0;
                }
            }
        }
        for p in 0..self.x.len() {
            let (base, fx, w) = stencil(self.x[p], inv_dx);
            let mut new_v = [0.0; 2];
            let mut new_c = [0.0; 4];
            for i in 0..3 {
                for j in 0..3 {
                    let dpos = [(i as f64 - fx[0]) * dx, (j as f64 - fx[1]) * dx];
                    let weight = w[0][i] * w[1][j];
                    let g = self.grid_v[(base[0] + i) * n + base[1] + j];
                    new_v[0] += weight * g[0];
                    new_v[1] += weight * g[1];
                    let s = 4.0 * weight * inv_dx * inv_dx;
                    new_c[0] += s * g[0] * dpos[0];
                    new_c[1] += s * g[0] * dpos[1];
                    new_c[2] += s * g[1] * dpos[0];
                    new_c[3] += s * g[1] * dpos[1];
                }
            }
            self.v[p] = new_v;
            self.x[p][0] += dt * new_v[0];
            self.x[p][1] += dt * new_v[1];
            self.j[p] *= 1.0 + dt * (new_c[0] + new_c[3]);
            self.c[p] = new_c;
        }
    }
}

/// The program's `base`, `fx` and quadratic B-spline weights `w` of a particle at `x`.
#[inline(always)]
fn stencil(x: [f64; 2], inv_dx: f64) -> ([usize; 2], [f64; 2], [[f64; 3]; 2]) {
    let xp = [x[0] * inv_dx, x[1] * inv_dx];
    let base = [(xp[0] - 0.5) as usize, (xp[1] - 0.5) as usize];
    let fx = [xp[0] - base[0] as f64, xp[1] - base[1] as f64];
    let w = |f: f64| {
        [
            0.5 * (1.5 - f) * (1.5 - f),
            0.75 - (f - 1.0) * (f - 1.0),
            0.5 * (f - 0.5) * (f - 0.5),
        ]
    };
    (base, fx, [w(fx[0]), w(fx[1])])
}
