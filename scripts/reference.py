"""Independent reference solutions for odyn's stiff tests (not run by CI).

Integrates van der Pol (mu = 1000, from (2, 0)) and Robertson kinetics (from (1, 0, 0)) with
SciPy's Radau (order 5, implicit) and BDF at tight tolerances and prints both, so the agreement
between two unrelated methods bounds the reference's own error. The values printed here are the
ones the tests in tests/integration/implicit.rs cite.

    pip install numpy scipy && python3 scripts/reference.py
"""

import numpy as np
import scipy
from scipy.integrate import solve_ivp

MU = 1000.0


def van_der_pol(t, y):
    return [y[1], MU * (1.0 - y[0] ** 2) * y[1] - y[0]]


def van_der_pol_jac(t, y):
    return [[0.0, 1.0], [-2.0 * MU * y[0] * y[1] - 1.0, MU * (1.0 - y[0] ** 2)]]


def robertson(t, y):
    a, b, c = y
    return [-0.04 * a + 1e4 * b * c, 0.04 * a - 1e4 * b * c - 3e7 * b * b, 3e7 * b * b]


def robertson_jac(t, y):
    a, b, c = y
    return [[-0.04, 1e4 * c, 1e4 * b], [0.04, -1e4 * c - 6e7 * b, -1e4 * b], [0.0, 6e7 * b, 0.0]]


def solve(name, f, jac, y0, times):
    print(f"{name} (scipy {scipy.__version__})")
    results = {}
    # BDF cannot go as tight as Radau on these problems; it serves as the independent check.
    for method, rtol, atol in (("Radau", 1e-12, 1e-14), ("BDF", 1e-9, 1e-12)):
        sol = solve_ivp(f, (0.0, times[-1]), y0, method=method, jac=jac, t_eval=times,
                        rtol=rtol, atol=atol)
        assert sol.success, sol.message
        results[method] = sol.y.T
    for i, t in enumerate(times):
        radau, bdf = results["Radau"][i], results["BDF"][i]
        spread = np.max(np.abs(radau - bdf))
        values = ", ".join(f"{v:.15e}" for v in radau)
        print(f"  t = {t:g}: [{values}]  |Radau - BDF| = {spread:.1e}")


if __name__ == "__main__":
    solve("van der Pol, mu = 1000, y(0) = (2, 0)", van_der_pol, van_der_pol_jac, [2.0, 0.0],
          [1.0, 10.0, 100.0, 808.0, 1000.0, 3000.0])
    solve("Robertson, y(0) = (1, 0, 0)", robertson, robertson_jac, [1.0, 0.0, 0.0],
          [0.4, 4.0, 40.0, 400.0, 4e4])
