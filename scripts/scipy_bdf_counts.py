"""SciPy's BDF step counts on the stiff problems `tests/integration/bdf.rs` compares `Bdf` with.

odyn's `Bdf` implements the algorithm of `scipy.integrate.BDF` (Shampine & Reichelt's NDFs,
orders 1-5): this prints, for the same problems, tolerances and analytic Jacobians, SciPy's
accepted steps (len(sol.t) - 1), f evaluations, Jacobian evaluations and LU factorizations, and
the final state's largest relative error against the references the tests use
(scripts/reference_stiff.py: the 36-digit Radau IIA value for ROBER, the Bari test set's for
HIRES and VDPOLM).

    pip install numpy scipy mpmath && python3 scripts/scipy_bdf_counts.py
"""

import warnings

import numpy as np
import scipy
from scipy.integrate import solve_ivp

from reference_stiff import BARI, hires, hires_jac, maxrel, robertson, robertson_jac, vdp, vdp_jac

PROBLEMS = [
    # name, f, J, y0, t_end, rtol, atol, reference
    ("robertson", robertson, robertson_jac, [1.0, 0.0, 0.0], 1e5, 1e-6, 1e-12,
     # mpRadau s = 7, dps = 36 (scripts/reference_stiff.py)
     [1.7865921142099464e-02, 7.274751468436319e-08, 9.821340061103858e-01]),
    ("hires", hires, hires_jac, [1, 0, 0, 0, 0, 0, 0, 0.0057], BARI["HIRES"][0], 1e-6, 1e-10,
     BARI["HIRES"][1]),
    ("van der pol", vdp, vdp_jac, [2.0, 0.0], 2000.0, 1e-6, 1e-9, BARI["VDPOL"][1]),
]


def main():
    print(f"scipy {scipy.__version__}, numpy {np.__version__}")
    print(f"{'problem':<12} {'rtol':>6} {'atol':>6} {'steps':>6} {'nfev':>6} {'njev':>5} "
          f"{'nlu':>5} {'error':>9}")
    for name, f, jac, y0, t_end, rtol, atol, reference in PROBLEMS:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            sol = solve_ivp(f, (0.0, t_end), y0, method="BDF", jac=jac, rtol=rtol, atol=atol)
        assert sol.success, sol.message
        error = maxrel(sol.y[:, -1], np.array(reference))
        print(f"{name:<12} {rtol:>6.0e} {atol:>6.0e} {len(sol.t) - 1:>6d} {sol.nfev:>6d} "
              f"{sol.njev:>5d} {sol.nlu:>5d} {error:>9.2e}")


if __name__ == "__main__":
    main()
