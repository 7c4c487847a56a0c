//! Models shared by the integration tests.
#![allow(
    dead_code,
    unused_imports,
    reason = "each test crate uses a different subset of these models"
)]

use odyn::prelude::*;

/// The scenes the tests share with the examples, benches and peers, written once (`scenes/`).
pub use scenes::{
    Arenstorf, Kepler, KeplerState, Lorenz, LorenzState, Robertson, RobertsonState, Spring,
    SpringState, VanDerPol, VanDerPolState, slope,
};

/// `f` run in a pool of its own with `threads` threads (the thread-count independence tests).
pub fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

/// A small deterministic generator (xorshift64*), so failures reproduce.
pub struct Rng(pub u64);

impl Rng {
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let bits = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11;
        lo + (hi - lo) * (bits as f64 / (1u64 << 53) as f64)
    }
}

/// Compares ∂f/∂y with central differences of f at `samples` random states drawn by `draw`.
/// The step h = 1e-6·(1 + |yⱼ|) leaves truncation and round-off errors near 1e-9 relative, so
/// 1e-6 relative (to the Jacobian's largest entry in the row) is a strict but safe bound.
pub fn check<M: odyn::Jacobian>(
    model: &M,
    t: f64,
    samples: usize,
    mut draw: impl FnMut(&mut Rng) -> M::State,
) where
    M::Matrix: odyn::DenseMatrix,
{
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for _ in 0..samples {
        let y = draw(&mut rng);
        let n = y.as_slice().len();
        let mut jacobian = model.jacobian_matrix(&y);
        model.jacobian(t, &y, &mut jacobian);
        for row in 0..n {
            let numeric: Vec<f64> = (0..n)
                .map(|column| central(model, t, &y, row, column))
                .collect();
            let scale = numeric.iter().map(|v| v.abs()).fold(1e-300, f64::max);
            for (column, fd) in numeric.iter().enumerate() {
                let exact = odyn::DenseMatrix::entry(&jacobian, row, column);
                assert!(
                    (exact - fd).abs() <= 1e-6 * scale,
                    "{} ∂f{row}/∂y{column} at {y:?}: generated {exact}, central difference {fd}",
                    M::NAME
                );
                // An empty pattern is an unknown one (a Jacobian of finite differences).
                if !M::NONZEROS.is_empty() && !M::NONZEROS.contains(&(row, column)) {
                    assert_eq!(
                        exact,
                        0.0,
                        "{}: ({row}, {column}) is a structural zero",
                        M::NAME
                    );
                }
            }
        }
    }
}

/// max |xᵢ − yᵢ| over the pairs of two equally long slices.
pub fn max_abs_difference(x: &[f64], y: &[f64]) -> f64 {
    x.iter()
        .zip(y)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
}

pub fn central<M: Model>(model: &M, t: f64, y: &M::State, row: usize, column: usize) -> f64 {
    let h = 1e-6 * (1.0 + y.as_slice()[column].abs());
    let (mut plus, mut minus) = (y.clone(), y.clone());
    plus.as_mut_slice()[column] += h;
    minus.as_mut_slice()[column] -= h;
    let (mut f_plus, mut f_minus) = (y.clone(), y.clone());
    model.derivative(t, &plus, &mut f_plus);
    model.derivative(t, &minus, &mut f_minus);
    (f_plus.as_slice()[row] - f_minus.as_slice()[row]) / (2.0 * h)
}

/// Undamped oscillator ẍ = −ω²x: its force never reads the velocity, so position Verlet takes it.
#[system(integrator = PositionVerlet)]
#[derive(Clone, Copy, Debug)]
pub struct Oscillator {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
    pub omega: f64,
}

#[system]
impl Oscillator {
    fn acceleration(&self) -> f64 {
        -self.omega * self.omega * self.x
    }

    /// Energy per unit mass.
    fn energy(&self) -> f64 {
        0.5 * self.v * self.v + 0.5 * self.omega * self.omega * self.x * self.x
    }
}

/// Two uncoupled oscillators as two position/velocity pairs, one driven by cos(t):
/// exercises tuple accelerations, array fields and the time argument.
#[system]
pub struct Pair {
    #[position]
    pub a: f64,
    #[position]
    pub b: [f64; 2],
    #[velocity]
    pub va: f64,
    #[velocity]
    pub vb: [f64; 2],
    pub drive: f64,
}

#[system]
impl Pair {
    fn acceleration(&self, t: f64) -> (f64, [f64; 2]) {
        (
            -self.a + self.drive * t.cos(),
            [-self.b[0], -4.0 * self.b[1]],
        )
    }
}

/// Simple pendulum θ̈ = −(g/L)·sin θ.
#[system(integrator = VelocityVerlet, dt = 0.01)]
pub struct Pendulum {
    #[position]
    pub theta: f64,
    #[velocity]
    pub omega: f64,
    pub g: f64,
    pub length: f64,
}

#[system]
impl Pendulum {
    fn acceleration(&self) -> f64 {
        -self.g / self.length * self.theta.sin()
    }

    fn energy(&self) -> f64 {
        0.5 * self.length * self.length * self.omega * self.omega
            + self.g * self.length * (1.0 - self.theta.cos())
    }
}

/// A charged particle in 3-D: Kepler attraction plus a magnetic (Lorentz) force q·v × B,
/// exercising `Vector3`, `cross`, `normalize` and vector parameters.
#[system(integrator = Rk4, dt = 0.01)]
pub struct Charged {
    #[position]
    pub r: Vector3<f64>,
    #[velocity]
    pub v: Vector3<f64>,
    pub gm: f64,
    pub qb: Vector3<f64>,
}

#[system]
impl Charged {
    fn acceleration(&self, t: f64) -> Vector3<f64> {
        let distance = self.r.norm();
        let radial = self.r.normalize();
        let lorentz = self.v.cross(&self.qb) * (1.0 + 0.1 * t.sin());
        -self.gm / (distance * distance) * radial + lorentz
    }
}

/// A force odyn cannot differentiate (a branch on the state), opted out of the Jacobian.
#[system(integrator = SymplecticEuler, jacobian = false)]
pub struct NoJacobian {
    #[position]
    pub x: f64,
    #[velocity]
    pub v: f64,
}

#[system]
impl NoJacobian {
    fn acceleration(&self) -> f64 {
        if self.x > 0.0 { -1.0 } else { 1.0 }
    }
}

/// Seventeen independent oscillators ẍᵢ = −ωᵢ²xᵢ with ωᵢ = i + 1: 34 state components, past the
/// 32 at which generated Jacobians move from the stack to faer.
#[system]
pub struct Bank {
    #[position]
    pub x: [f64; 17],
    #[velocity]
    pub v: [f64; 17],
}

#[system]
impl Bank {
    fn acceleration(&self) -> [f64; 17] {
        let x = self.x;
        [
            -x[0],
            -4.0 * x[1],
            -9.0 * x[2],
            -16.0 * x[3],
            -25.0 * x[4],
            -36.0 * x[5],
            -49.0 * x[6],
            -64.0 * x[7],
            -81.0 * x[8],
            -100.0 * x[9],
            -121.0 * x[10],
            -144.0 * x[11],
            -169.0 * x[12],
            -196.0 * x[13],
            -225.0 * x[14],
            -256.0 * x[15],
            -289.0 * x[16],
        ]
    }
}

/// A ball under gravity, ÿ = −g (its bounces are events).
#[system]
#[derive(Clone, Copy, Debug)]
pub struct Ball {
    #[position]
    pub y: f64,
    #[velocity]
    pub v: f64,
    pub g: f64,
}

#[system]
impl Ball {
    fn acceleration(&self) -> f64 {
        -self.g
    }

    fn energy(&self) -> f64 {
        0.5 * self.v * self.v + self.g * self.y
    }
}

/// A global allocator that counts allocations (and reallocations) and hands them to the system
/// allocator, for the allocation tests: each registers it with
/// `#[global_allocator] static GLOBAL: common::Counting = common::Counting;` in a binary of one
/// test, so no other test's allocations are counted, and calls [`count_this_thread`] first.
/// Only that thread's allocations count: the test harness's main thread may still be allocating
/// for the test it just spawned when the test takes its first count (four allocations at a
/// random moment, seen on a loaded machine); odyn steps on the calling thread.
pub struct Counting;

/// Allocations made so far under [`Counting`] by threads that called [`count_this_thread`].
pub static ALLOCATIONS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

thread_local! {
    /// Whether this thread's allocations count (const-initialized, so reading it allocates
    /// nothing).
    static COUNTED: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Counts the calling thread's allocations in [`ALLOCATIONS`] from now on.
pub fn count_this_thread() {
    COUNTED.with(|counted| counted.set(true));
}

fn count() {
    if COUNTED.try_with(|counted| counted.get()).unwrap_or(false) {
        ALLOCATIONS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    }
}

// SAFETY: forwards every call to `System` unchanged.
unsafe impl std::alloc::GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: std::alloc::Layout) -> *mut u8 {
        count();
        // SAFETY: the caller's contract is passed on.
        unsafe { std::alloc::System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: std::alloc::Layout) {
        // SAFETY: the caller's contract is passed on.
        unsafe { std::alloc::System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: std::alloc::Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: the caller's contract is passed on.
        unsafe { std::alloc::System.realloc(ptr, layout, new_size) }
    }
}
