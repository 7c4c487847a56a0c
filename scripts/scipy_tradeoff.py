"""SciPy's solve_ivp on odyn's tradeoff scenes, at matched accuracy (not run by CI).

For each scene and each of RK45, DOP853 and Radau, sweeps rtol and records the final-state error
(against the same references `examples/tradeoff.rs` uses) and the wall time (best of 3). Then, for
every SciPy run, finds odyn's fastest run in out/tradeoff/<scene>.csv that is at least as accurate
and prints how many times faster it is. Run the odyn example first:

    cargo run --release --example tradeoff
    pip install numpy scipy && python3 scripts/scipy_tradeoff.py
"""

import csv
import math
import os
import time

import numpy as np
from scipy.integrate import solve_ivp

OUT = "out/tradeoff"


def spring(t, y):
    return [y[1], -50.0 * y[0] - 0.5 * y[1]]


def spring_jac(t, y):
    return [[0.0, 1.0], [-50.0, -0.5]]


def spring_exact(t):
    k, b, m = 50.0, 0.5, 1.0
    g = b / (2 * m)
    w = math.sqrt(k / m - g * g)
    a, bb = 1.0, g / w
    e = math.exp(-g * t)
    s, c = math.sin(w * t), math.cos(w * t)
    return [e * (a * c + bb * s), e * ((bb * w - g * a) * c - (a * w + g * bb) * s)]


def lorenz(t, y):
    return [10.0 * (y[1] - y[0]), y[0] * (28.0 - y[2]) - y[1], y[0] * y[1] - 8.0 / 3.0 * y[2]]


def lorenz_jac(t, y):
    return [[-10.0, 10.0, 0.0], [28.0 - y[2], -1.0, -y[0]], [y[1], y[0], -8.0 / 3.0]]


def robertson(t, y):
    a, b, c = y
    return [-0.04 * a + 1e4 * b * c, 0.04 * a - 1e4 * b * c - 3e7 * b * b, 3e7 * b * b]


def robertson_jac(t, y):
    a, b, c = y
    return [[-0.04, 1e4 * c, 1e4 * b], [0.04, -1e4 * c - 6e7 * b, -1e4 * b], [0.0, 6e7 * b, 0.0]]


def kepler(t, y):
    r3 = (y[0] ** 2 + y[1] ** 2) ** 1.5
    return [y[2], y[3], -y[0] / r3, -y[1] / r3]


def kepler_exact(t):
    e, n = 0.5, 1.0
    mean = (n * t) % (2 * math.pi)
    ecc = mean + e * math.sin(mean)
    for _ in range(50):
        d = (ecc - e * math.sin(ecc) - mean) / (1 - e * math.cos(ecc))
        ecc -= d
        if abs(d) < 1e-15:
            break
    b, rate = math.sqrt(1 - e * e), n / (1 - e * math.cos(ecc))
    return [math.cos(ecc) - e, b * math.sin(ecc), -math.sin(ecc) * rate, b * math.cos(ecc) * rate]


SCENES = {
    # scene: (f, jac, y0, horizon, reference final state)
    "spring": (spring, spring_jac, [1.0, 0.0], 10.0, spring_exact(10.0)),
    "lorenz": (lorenz, lorenz_jac, [1.0, 1.0, 1.0], 1.0, None),  # reference: DOP853 at rtol 1e-13
    "robertson": (robertson, robertson_jac, [1.0, 0.0, 0.0], 40.0,
                  [7.158270687199023e-01, 9.185534764554085e-06, 2.841637457453337e-01]),
    "kepler": (kepler, None, [0.5, 0.0, 0.0, math.sqrt(3.0)], 1000 * 2 * math.pi,
               kepler_exact(1000 * 2 * math.pi)),
}


def run(f, jac, y0, horizon, method, rtol):
    kwargs = {"jac": jac} if method == "Radau" and jac is not None else {}
    best = math.inf
    for _ in range(3):
        start = time.perf_counter()
        sol = solve_ivp(f, (0.0, horizon), y0, method=method, rtol=rtol, atol=rtol * 1e-3, **kwargs)
        best = min(best, time.perf_counter() - start)
        if best > 1.0:
            break  # one timing is enough for a run this long
    return sol, best


# The tolerances each method is swept over; pure-Python right-hand sides make the tightest
# settings of the low-order methods take minutes on the long Kepler run, so they stop earlier.
TOLERANCES = {"RK45": (1e-3, 1e-5, 1e-7), "DOP853": (1e-3, 1e-5, 1e-7, 1e-9, 1e-11), "Radau": (1e-3, 1e-5, 1e-7, 1e-9)}


def odyn_runs(scene):
    path = os.path.join(OUT, f"{scene}.csv")
    if not os.path.exists(path):
        return []
    with open(path) as f:
        rows = list(csv.DictReader(f))
    # A fixed-step run has a dt, an adaptive one (Tsit5, DOP853, the Rosenbrock methods, BDF)
    # an rtol instead.
    return [(r["method"], f"dt {float(r['dt']):.3g}" if r["dt"] else f"rtol {float(r['rtol']):.0e}",
             float(r["error"]), float(r["seconds"])) for r in rows
            if math.isfinite(float(r["error"])) and math.isfinite(float(r["seconds"]))]


def main():
    os.makedirs(OUT, exist_ok=True)
    for scene, (f, jac, y0, horizon, reference) in SCENES.items():
        if reference is None:
            ref = solve_ivp(f, (0.0, horizon), y0, method="DOP853", rtol=1e-13, atol=1e-16)
            reference = ref.y[:, -1]
        rows = []
        ours = odyn_runs(scene)
        print(f"\n{scene}: SciPy solve_ivp against odyn's fastest run at least as accurate")
        for method in ("RK45", "DOP853", "Radau"):
            for rtol in TOLERANCES[method]:
                if scene == "kepler" and (method == "Radau" or rtol < 1e-9):
                    continue  # minutes per run in pure Python over 1000 orbits
                if scene == "robertson" and method != "Radau" and rtol < 1e-5:
                    continue  # explicit methods on a stiff problem at tight tolerance take minutes
                sol, seconds = run(f, jac, y0, horizon, method, rtol)
                if not sol.success:
                    print(f"  {method:>6} rtol {rtol:.0e}: failed ({sol.message})")
                    continue
                error = float(np.max(np.abs(sol.y[:, -1] - np.asarray(reference))))
                rows.append([scene, method, rtol, error, seconds, sol.nfev, sol.njev])
                better = [o for o in ours if o[2] <= error]
                if better:
                    name, setting, oerr, osec = min(better, key=lambda o: o[3])
                    print(f"  {method:>6} rtol {rtol:.0e}: error {error:.2e} in {seconds * 1e3:8.3f} ms; "
                          f"odyn {name} {setting}: {oerr:.2e} in {osec * 1e3:8.3f} ms -> {seconds / osec:7.1f}x faster")
                else:
                    print(f"  {method:>6} rtol {rtol:.0e}: error {error:.2e} in {seconds * 1e3:8.3f} ms; "
                          f"no odyn run that accurate")
        with open(os.path.join(OUT, f"scipy_{scene}.csv"), "w", newline="") as out:
            w = csv.writer(out)
            w.writerow(["scene", "method", "rtol", "error", "seconds", "nfev", "njev"])
            w.writerows(rows)


if __name__ == "__main__":
    main()
