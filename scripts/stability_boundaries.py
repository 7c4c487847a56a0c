"""Imaginary-axis stability boundaries of odyn's explicit Runge–Kutta tableaux (not run by CI).

For an explicit Runge–Kutta method with tableau (A, b) the stability polynomial is
R(z) = sum_k gamma_k z^k with gamma_0 = 1 and gamma_k = b^T A^(k-1) 1 (Hairer & Wanner, Solving
ODEs II, §IV.2). On an undamped oscillator (eigenvalues ±iω) a fixed step h is stable while
|R(iωh)| <= 1; this script finds, in 40-digit arithmetic, the first y > 0 with |R(iy)| = 1 for
Tsit5 and DOP853, reading the coefficients from runtime/src/integrators/tableaux/*.rs. The values
printed are the ones tests/stability.rs cites.

    pip install mpmath numpy && python3 scripts/stability_boundaries.py
"""

import os
import re

import mpmath as mp

mp.mp.dps = 40
HERE = os.path.dirname(os.path.abspath(__file__))
TABLEAUX = os.path.join(HERE, "..", "runtime", "src", "integrators", "tableaux")


def read(path, name):
    text = open(path, encoding="utf-8").read()
    body = re.search(r"const %s: \[[^=]*= (\[.*?\]);\n" % name, text, re.S).group(1)
    body = re.sub(r"//[^\n]*", "", body)
    return [mp.mpf(x) for x in re.findall(r"-?\d+\.?\d*(?:e-?\d+)?", body)]


def polynomial(file, stages):
    a = read(os.path.join(TABLEAUX, file), "A")
    b = read(os.path.join(TABLEAUX, file), "B")
    a = mp.matrix([a[i * stages:(i + 1) * stages] for i in range(stages)])
    b = mp.matrix(b)
    gamma, v = [mp.mpf(1)], mp.matrix([1] * stages)
    for _ in range(stages):
        gamma.append((b.T * v)[0])
        v = a * v
    return gamma


def excess(gamma, y):
    return abs(sum(c * (1j * y) ** k for k, c in enumerate(gamma))) - 1


for name, file, stages in (("Tsit5", "tsit5.rs", 7), ("DOP853", "dop853.rs", 12)):
    gamma = polynomial(file, stages)
    # Scan for the first sign change of |R(iy)| - 1 (ignoring round-off at tiny y), then refine.
    y, step = mp.mpf("0.01"), mp.mpf("0.001")
    while excess(gamma, y) <= mp.mpf("1e-30"):
        y += step
    root = mp.findroot(lambda s: excess(gamma, s), (y - step, y), solver="anderson")
    print(f"{name}: |R(iy)| = 1 first at y = {mp.nstr(root, 16)}")
