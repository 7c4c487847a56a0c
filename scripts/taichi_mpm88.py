"""odyn's MLS-MPM against Taichi's CPU backend on the 88-line program's scene (not run by CI).

The scene is `mpm88.py`, the 88-line MLS-MPM program that ships with Taichi (Hu et al.,
SIGGRAPH 2018): N particles of a weakly compressible fluid (unit density, E = 400, Kirchhoff
pressure E(J - 1)) dropped at 1 m/s from the square [0.2, 0.6]^2 in a unit box of n_grid^2 nodes,
walls 3 nodes thick, gravity 9.8, dt = 2e-4, APIC transfers. At 8192 particles the grid is
Taichi's 128^2; at 32k and 128k particles the grid grows as sqrt(N) (256^2, 512^2) and dt shrinks
as the node spacing, so every size has the same particles per cell and Courant number.

Both programs start from the same positions (drawn here with NumPy, seed 0, sorted by grid cell
row by row, and read by odyn's `examples/mpm88.rs`); after CHECK substeps both positions are compared, which shows the scene is
the same one, and then each is timed over the same substeps (best of REPEATS, after a warm-up
that includes Taichi's JIT compilation). Taichi runs in double precision on 2 CPU threads (and 1
for reference); odyn on 1 and 2 rayon threads.

    python3 scripts/taichi_mpm88.py [--sizes 8192,32768,131072]

installs taichi==1.7.4 with pip when it is missing, builds odyn's example in release mode, and
prints ms per substep and the ratios.
"""

import argparse
import os
import subprocess
import sys
import time

import numpy as np

REPEATS = 3
CHECK = 20
TAICHI = "1.7.4"


def ensure_taichi():
    try:
        import taichi  # noqa: F401
    except ImportError:
        print(f"installing taichi=={TAICHI} with pip", file=sys.stderr)
        subprocess.run([sys.executable, "-m", "pip", "install", "-q", f"taichi=={TAICHI}"],
                       check=True)


def scene(n_particles):
    n_grid = int(round(128 * (n_particles / 8192) ** 0.5))
    dt = 2e-4 * 128 / n_grid
    rng = np.random.default_rng(0)
    x = rng.random((n_particles, 2)) * 0.4 + 0.2
    # Sorted by grid cell, row by row (stably), as scenes::hybrid::mpm88 sorts its own: the
    # order a block's lattice has. The same order goes to every runner.
    cells = np.floor(x * n_grid).astype(int)
    x = x[np.lexsort((cells[:, 0], cells[:, 1]))]
    return n_grid, dt, x


def taichi_run(n_particles, n_grid, dt, x0, threads, substeps):
    """mpm88.py, as shipped with Taichi, in f64; returns (positions after CHECK substeps,
    ms per substep)."""
    import taichi as ti

    ti.init(arch=ti.cpu, default_fp=ti.f64, cpu_max_num_threads=threads, log_level=ti.ERROR)
    dx = 1 / n_grid
    p_rho = 1
    p_vol = (dx * 0.5) ** 2
    p_mass = p_vol * p_rho
    gravity = 9.8
    bound = 3
    E = 400

    x = ti.Vector.field(2, float, n_particles)
    v = ti.Vector.field(2, float, n_particles)
    C = ti.Matrix.field(2, 2, float, n_particles)
    J = ti.field(float, n_particles)
    grid_v = ti.Vector.field(2, float, (n_grid, n_grid))
    grid_m = ti.field(float, (n_grid, n_grid))

    @ti.kernel
    def substep():
        for i, j in grid_m:
            grid_v[i, j] = [0, 0]
            grid_m[i, j] = 0
        for p in x:
            Xp = x[p] / dx
            base = int(Xp - 0.5)
            fx = Xp - base
            w = [0.5 * (1.5 - fx) ** 2, 0.75 - (fx - 1) ** 2, 0.5 * (fx - 0.5) ** 2]
            stress = -dt * 4 * E * p_vol * (J[p] - 1) / dx**2
            affine = ti.Matrix([[stress, 0], [0, stress]]) + p_mass * C[p]
            for i, j in ti.static(ti.ndrange(3, 3)):
                offset = ti.Vector([i, j])
                dpos = (offset - fx) * dx
                weight = w[i].x * w[j].y
                grid_v[base + offset] += weight * (p_mass * v[p] + affine @ dpos)
                grid_m[base + offset] += weight * p_mass
        for i, j in grid_m:
            if grid_m[i, j] > 0:
                grid_v[i, j] /= grid_m[i, j]
            grid_v[i, j].y -= dt * gravity
            if i < bound and grid_v[i, j].x < 0:
                grid_v[i, j].x = 0
            if i > n_grid - bound and grid_v[i, j].x > 0:
                grid_v[i, j].x = 0
            if j < bound and grid_v[i, j].y < 0:
                grid_v[i, j].y = 0
            if j > n_grid - bound and grid_v[i, j].y > 0:
                grid_v[i, j].y = 0
        for p in x:
            Xp = x[p] / dx
            base = int(Xp - 0.5)
            fx = Xp - base
            w = [0.5 * (1.5 - fx) ** 2, 0.75 - (fx - 1.0) ** 2, 0.5 * (fx - 0.5) ** 2]
            new_v = ti.Vector.zero(float, 2)
            new_C = ti.Matrix.zero(float, 2, 2)
            for i, j in ti.static(ti.ndrange(3, 3)):
                offset = ti.Vector([i, j])
                dpos = (offset - fx) * dx
                weight = w[i].x * w[j].y
                g_v = grid_v[base + offset]
                new_v += weight * g_v
                new_C += 4 * weight * g_v.outer_product(dpos) / dx**2
            v[p] = new_v
            x[p] += dt * v[p]
            J[p] *= 1 + dt * new_C.trace()
            C[p] = new_C

    def reset():
        x.from_numpy(x0)
        v.from_numpy(np.tile([0.0, -1.0], (n_particles, 1)))
        J.from_numpy(np.ones(n_particles))
        C.from_numpy(np.zeros((n_particles, 2, 2)))

    reset()
    for _ in range(CHECK):
        substep()
    checked = x.to_numpy()
    best = float("inf")
    for _ in range(REPEATS):
        reset()
        substep()
        ti.sync()
        start = time.perf_counter()
        for _ in range(substeps):
            substep()
        ti.sync()
        best = min(best, (time.perf_counter() - start) / substeps)
    ti.reset()
    return checked, 1e3 * best


def odyn_run(n_grid, dt, positions_file, threads, substeps):
    """examples/mpm88.rs on the same positions; returns (positions after CHECK substeps, ms per
    substep)."""
    out = positions_file.replace(".csv", f"_odyn_{threads}.csv")
    result = subprocess.run(
        ["cargo", "run", "-q", "--release", "--example", "mpm88", "--",
         "--input", positions_file, "--grid", str(n_grid), "--dt", repr(dt),
         "--threads", str(threads), "--substeps", str(substeps), "--repeats", str(REPEATS),
         "--check", str(CHECK), "--output", out],
        check=True, capture_output=True, text=True)
    ms = float(result.stdout.split("ms per substep")[0].split()[-1])
    return np.loadtxt(out, delimiter=",", skiprows=1), ms


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--sizes", default="8192,32768,131072")
    args = parser.parse_args()
    ensure_taichi()
    import taichi as ti

    os.chdir(os.path.join(os.path.dirname(__file__), ".."))
    os.makedirs("target/race", exist_ok=True)
    subprocess.run(["cargo", "build", "-q", "--release", "--example", "mpm88"], check=True)
    print(f"taichi {ti.__version__}, f64, CPU backend; odyn examples/mpm88.rs (release)")
    print(f"{'particles':>9} {'grid':>5} {'dt':>8} | {'taichi 2t':>9} {'taichi 1t':>9} | "
          f"{'odyn 1t':>8} {'odyn 2t':>8} | {'taichi2/odyn2':>13} {'same scene':>10}")
    for n in [int(s) for s in args.sizes.split(",")]:
        n_grid, dt, x0 = scene(n)
        substeps = max(100, 16_000_000 // n)
        path = f"target/race/mpm88_{n}.csv"
        np.savetxt(path, x0, delimiter=",", header="x,y", comments="", fmt="%.17g")
        t_x, taichi2 = taichi_run(n, n_grid, dt, x0, 2, substeps)
        _, taichi1 = taichi_run(n, n_grid, dt, x0, 1, substeps)
        o_x, odyn1 = odyn_run(n_grid, dt, path, 1, substeps)
        o_x2, odyn2 = odyn_run(n_grid, dt, path, 2, substeps)
        assert np.array_equal(o_x, o_x2), "odyn differs between 1 and 2 threads"
        same = np.abs(o_x - t_x).max()
        print(f"{n:>9} {n_grid:>5} {dt:>8.2e} | {taichi2:>9.3f} {taichi1:>9.3f} | "
              f"{odyn1:>8.3f} {odyn2:>8.3f} | {taichi2 / odyn2:>12.2f}x {same:>10.1e}")
    print(f"ms per substep, best of {REPEATS}; 'same scene': largest difference of a particle's "
          f"position (m) between Taichi and odyn after {CHECK} substeps from the same start")


if __name__ == "__main__":
    main()
