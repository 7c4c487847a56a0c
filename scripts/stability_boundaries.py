"""Imaginary-axis stability boundaries of odyn's explicit Runge–Kutta tableaux (not run by CI).

For an explicit Runge–Kutta method with tableau (A, b) the stability polynomial is
R(z) = sum_k gamma_k z^k with gamma_0 = 1 and gamma_k = b^T A^(k-1) 1 (Hairer & Wanner, Solving
ODEs II, §IV.2). On an undamped oscillator (eigenvalues ±iω) a fixed step h is stable while
|R(iωh)| <= 1; this script finds, in 40-digit arithmetic, the first y > 0 with |R(iy)| = 1 for
Tsit5 and DOP853, reading the coefficients from runtime/src/integrators/tableaux/*.rs. It also
finds the oscillator limits of the leapfrog compositions (Yoshida4, Yoshida6, KahanLi6) from their
composed one-step matrices. The values printed are the ones tests/integration/stability.rs cites.

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


# Compositions of leapfrog (Yoshida 1990; Kahan & Li 1997, as in HLW, Geometric Numerical
# Integration, V.3): on x'' = -x a leapfrog step of size z maps (x, v) by
# M(z) = [[1 - z^2/2, z], [-z (1 - z^2/4), 1 - z^2/2]]; the composition's matrix is the product
# over the weights, det = 1, and it is stable while |trace| <= 2.
def composition_limit(weights):
    def trace_excess(z):
        p = mp.eye(2)
        for g in weights:
            w = g * z
            p = mp.matrix([[1 - w ** 2 / 2, w], [-w * (1 - w ** 2 / 4), 1 - w ** 2 / 2]]) * p
        return abs(p[0, 0] + p[1, 1]) - 2
    z, step = mp.mpf("0.001"), mp.mpf("0.001")
    while trace_excess(z) <= 0:
        z += step
    lo, hi = z - step, z
    for _ in range(200):
        mid = (lo + hi) / 2
        lo, hi = (lo, mid) if trace_excess(mid) > 0 else (mid, hi)
    return lo


cbrt2 = mp.cbrt(2)
y6 = [mp.mpf("0.78451361047755726381949763"), mp.mpf("0.23557321335935813368479318"),
      mp.mpf("-1.17767998417887100694641568")]
kl = [mp.mpf("0.39216144400731413927925056"), mp.mpf("0.33259913678935943859974864"),
      mp.mpf("-0.70624617255763935980996482"), mp.mpf("0.08221359629355080023149045"),
      mp.mpf("0.79854399093482996339895035")]
for name, weights in (
        ("Yoshida4", [1 / (2 - cbrt2), -cbrt2 / (2 - cbrt2), 1 / (2 - cbrt2)]),
        ("Yoshida6", y6 + [1 - 2 * sum(y6)] + y6[::-1]),
        ("KahanLi6", kl + kl[-2::-1])):
    print(f"{name}: stable for omega*h < {mp.nstr(composition_limit(weights), 16)}")
    # Where |trace| > 2 again after the first limit: gaps of instability up to omega*h = 4.
    z, edges, unstable = mp.mpf("0.001"), [], False
    while z < 4:
        p = mp.eye(2)
        for g in weights:
            w = g * z
            p = mp.matrix([[1 - w ** 2 / 2, w], [-w * (1 - w ** 2 / 4), 1 - w ** 2 / 2]]) * p
        if (abs(p[0, 0] + p[1, 1]) > 2) != unstable:
            unstable = not unstable
            edges.append(mp.nstr(z, 4))
        z += mp.mpf("0.001")
    print(f"    unstable from / stable again at (step 1e-3): {', '.join(edges)}")
