#!/usr/bin/env python3
"""Fixed- and variable-step prototype of Rodas5P and Rosenbrock23 (ode23s).

Purpose: show that the coefficients in ``runtime/src/integrators/tableaux/rodas5p.rs`` and
the formulas in ``rosenbrock23.rs-notes.md`` are right, by measuring
convergence orders and by solving Robertson's stiff problem.

The Rodas5P numbers are *parsed from that file*, so the digits that
are tested are the ones that ship. A second, independent transcription (from
the scalar-per-field copy of the tableau) is compared against them digit for
digit.

Conventions (see the .rs header and the notes for details):

Rodas5P, one step (t, y) -> t + h, J = df/dy(t, y), ft = df/dt(t, y):
    U_i   = y + sum_{j<i} a_ij u_j
    (I/(h*gamma) - J) u_i = f(t + c_i h, U_i) + sum_{j<i} (C_ij/h) u_j + h d_i ft
    y_new = U_8 + u_8,  error estimate = u_8
    K_r   = sum_j H_rj u_j
    y(t+th*h) = (1-th) y + th (y_new + (1-th)(K_1 + th (K_2 + th K_3)))

Rosenbrock23 (Shampine & Reichelt 1997, ode23s), d = 1/(2+sqrt2), e32 = 6+sqrt2:
    W  = I - h d J,   F0 = f(t, y),  T = df/dt(t, y)
    k1 = W^{-1} (F0 + h d T)
    F1 = f(t + h/2, y + h/2 k1)
    k2 = W^{-1} (F1 - k1) + k1
    y_new = y + h k2
    F2 = f(t + h, y_new)
    k3 = W^{-1} (F2 - e32 (k2 - F1) - 2 (k1 - F0) + h d T)
    error estimate = h/6 (k1 - 2 k2 + k3)
    y(t + s h) = y + h (s(1-s)/(1-2d) k1 + s(s-2d)/(1-2d) k2)
"""

import math
import os
import re
import sys
import time

import numpy as np
import scipy
from scipy.integrate import solve_ivp
from scipy.linalg import lu_factor, lu_solve

HERE = os.path.dirname(os.path.abspath(__file__))


# --------------------------------------------------------------------------
# Tableau loading (from the Rust file)
# --------------------------------------------------------------------------

def _parse_rust_const(text, name):
    """Return the numbers of `pub(super) const NAME: ... = <value>;` as floats."""
    m = re.search(r"pub\(in crate::integrators\) const " + re.escape(name) + r"\s*:[^=]*=\s*(.*?);",
                  text, re.S)
    if not m:
        raise SystemExit(f"constant {name} not found in rodas5p.rs")
    nums = re.findall(r"-?\d+\.\d+(?:[eE][-+]?\d+)?", m.group(1))
    return [float(x) for x in nums], nums


def load_rodas5p():
    path = os.path.join(HERE, "..", "runtime", "src", "integrators", "tableaux", "rodas5p.rs")
    with open(path, encoding="utf-8") as fh:
        text = fh.read()
    g, g_lit = _parse_rust_const(text, "GAMMA")
    a, a_lit = _parse_rust_const(text, "A")
    C, C_lit = _parse_rust_const(text, "COUPLING")
    c, c_lit = _parse_rust_const(text, "C")
    d, d_lit = _parse_rust_const(text, "D")
    H, H_lit = _parse_rust_const(text, "H")
    assert len(g) == 1 and len(a) == 64 and len(C) == 64
    assert len(c) == 8 and len(d) == 8 and len(H) == 24
    literals = g_lit + a_lit + C_lit + c_lit + d_lit + H_lit
    tab = dict(gamma=g[0], a=np.array(a).reshape(8, 8), C=np.array(C).reshape(8, 8),
               c=np.array(c), d=np.array(d), H=np.array(H).reshape(3, 8))
    return tab, literals


# Independent second transcription, from the scalar-per-field copy of the same
# tableau (a21 = ..., C21 = ..., h21 = ...). Numbers only.
SCALAR_COPY = {
    "gamma": 0.21193756319429014,
    "a": {(2, 1): 3.0,
          (3, 1): 2.849394379747939, (3, 2): 0.45842242204463923,
          (4, 1): -6.954028509809101, (4, 2): 2.489845061869568, (4, 3): -10.358996098473584,
          (5, 1): 2.8029986275628964, (5, 2): 0.5072464736228206, (5, 3): -0.3988312541770524,
          (5, 4): -0.04721187230404641,
          (6, 1): -7.502846399306121, (6, 2): 2.561846144803919, (6, 3): -11.627539656261098,
          (6, 4): -0.18268767659942256, (6, 5): 0.030198172008377946},
    "C": {(2, 1): -14.155112264123755,
          (3, 1): -17.97296035885952, (3, 2): -2.859693295451294,
          (4, 1): 147.12150275711716, (4, 2): -1.41221402718213, (4, 3): 71.68940251302358,
          (5, 1): 165.43517024871676, (5, 2): -0.4592823456491126, (5, 3): 42.90938336958603,
          (5, 4): -5.961986721573306,
          (6, 1): 24.854864614690072, (6, 2): -3.0009227002832186, (6, 3): 47.4931110020768,
          (6, 4): 5.5814197821558125, (6, 5): -0.6610691825249471,
          (7, 1): 30.91273214028599, (7, 2): -3.1208243349937974, (7, 3): 77.79954646070892,
          (7, 4): 34.28646028294783, (7, 5): -19.097331116725623, (7, 6): -28.087943162872662,
          (8, 1): 37.80277123390563, (8, 2): -3.2571969029072276, (8, 3): 112.26918849496327,
          (8, 4): 66.9347231244047, (8, 5): -40.06618937091002, (8, 6): -54.66780262877968,
          (8, 7): -9.48861652309627},
    "c": {2: 0.6358126895828704, 3: 0.4095798393397535, 4: 0.9769306725060716,
          5: 0.4288403609558664},
    "d": {1: 0.21193756319429014, 2: -0.42387512638858027, 3: -0.3384627126235924,
          4: 1.8046452872882734, 5: 2.325825639765069},
    "H": {1: [25.948786856663858, -2.5579724845846235, 10.433815404888879, -2.3679251022685204,
              0.524948541321073, 1.1241088310450404, 0.4272876194431874, -0.17202221070155493],
          2: [-9.91568850695171, -0.9689944594115154, 3.0438037242978453, -24.495224566215796,
              20.176138334709044, 15.98066361424651, -6.789040303419874, -6.710236069923372],
          3: [11.419903575922262, 2.8879645146136994, 72.92137995996029, 80.12511834622643,
              -52.072871366152654, -59.78993625266729, -0.15582684282751913, 4.883087185713722]},
}


def check_tableau(tab, literals):
    print("== Rodas5P tableau checks ==")
    # 1. Bit-exact comparison with the second transcription.
    g = SCALAR_COPY["gamma"]
    a = np.zeros((8, 8))
    C = np.zeros((8, 8))
    for (i, j), v in SCALAR_COPY["a"].items():
        a[i - 1, j - 1] = v
    a[6, :5] = a[5, :5]
    a[6, 5] = 1.0          # stiffly accurate continuation (a76 = 1)
    a[7, :5] = a[5, :5]
    a[7, 5] = a[7, 6] = 1.0  # a86 = a87 = 1
    for (i, j), v in SCALAR_COPY["C"].items():
        C[i - 1, j - 1] = v
    c = np.array([0.0] + [SCALAR_COPY["c"][k] for k in range(2, 6)] + [1.0, 1.0, 1.0])
    d = np.array([SCALAR_COPY["d"][k] for k in range(1, 6)] + [0.0, 0.0, 0.0])
    H = np.array([SCALAR_COPY["H"][r] for r in (1, 2, 3)])
    same = (g == tab["gamma"] and np.array_equal(a, tab["a"]) and np.array_equal(C, tab["C"])
            and np.array_equal(c, tab["c"]) and np.array_equal(d, tab["d"])
            and np.array_equal(H, tab["H"]))
    print(f"  .rs constants == independent scalar-copy transcription (bit-exact): {same}")
    # 2. Every literal is the shortest round-trip representation of its f64.
    bad = [s for s in literals if repr(float(s)) != s.lstrip("+")]
    print(f"  literals that are not shortest round-trip f64 reprs: {bad if bad else 'none'}"
          f" ({len(literals)} literals)")
    # 3. Recover the classical ROW coefficients and check c, d, b.
    gam = tab["gamma"]
    Gam = np.linalg.inv(np.eye(8) / gam - tab["C"])     # Γ = (I/γ − C)^{-1}
    alpha = tab["a"] @ Gam                              # α = a Γ
    b = np.append(tab["a"][7, :7], 1.0) @ Gam           # m = (a_8*, 1) -> b = m Γ
    print(f"  diag(Gamma) - gamma, max |.|           : {np.max(np.abs(np.diag(Gam) - gam)):.2e}")
    print(f"  max |sum_j alpha_ij - c_i|             : {np.max(np.abs(alpha.sum(1) - tab['c'])):.2e}")
    print(f"  max |sum_j gamma_ij - d_i| (incl diag) : {np.max(np.abs(Gam.sum(1) - tab['d'])):.2e}")
    beta = alpha + Gam - np.diag(np.diag(Gam))          # strictly-lower α_ij + γ_ij
    bp = beta.sum(1)
    al = alpha.sum(1)
    print(f"  order cond. sum b_i = 1                : {b.sum() - 1: .2e}")
    print(f"  order cond. sum b_i beta'_i = 1/2-gamma: {b @ bp - (0.5 - gam): .2e}")
    print(f"  order cond. sum b_i alpha_i^2 = 1/3    : {b @ al**2 - 1/3: .2e}")
    print(f"  order cond. sum b_i beta_ij beta'_j = 1/6-gamma+gamma^2: "
          f"{b @ (beta @ bp) - (1/6 - gam + gam**2): .2e}")
    print(f"  order cond. sum b_i alpha_i^3 = 1/4    : {b @ al**3 - 0.25: .2e}")
    print(f"  order cond. sum b_i alpha_i^4 = 1/5    : {b @ al**4 - 0.2: .2e}")
    print("  recovered b =", np.array2string(b, precision=6, max_line_width=200))
    # Stiff accuracy in the classical form: b_i = alpha_8i + gamma_8i.
    print(f"  stiffly accurate: max |b - (alpha_8 + Gamma_8)| = "
          f"{np.max(np.abs(b - (alpha[7] + Gam[7]))):.2e}")
    return same and not bad


# --------------------------------------------------------------------------
# Steppers
# --------------------------------------------------------------------------

class Counter:
    def __init__(self):
        self.nf = 0
        self.njac = 0
        self.nlu = 0
        self.nsolve = 0


def rodas5p_step(tab, f, jac, ft, t, y, h, cnt, use_ft=True, jac_override=None):
    """One Rodas5P step. Returns (y_new, err_est, dense_K (3,n))."""
    g = tab["gamma"]
    a, C, c, d, H = tab["a"], tab["C"], tab["c"], tab["d"], tab["H"]
    n = y.size
    J = jac(t, y) if jac_override is None else jac_override(t, y)
    Ft = ft(t, y) if use_ft else np.zeros(n)
    cnt.njac += 1
    lu = lu_factor(np.eye(n) / (h * g) - J)
    cnt.nlu += 1
    u = np.zeros((8, n), dtype=np.result_type(y, J))
    U = y
    for i in range(8):
        U = y + a[i, :i] @ u[:i]
        rhs = f(t + c[i] * h, U) + (C[i, :i] / h) @ u[:i] + (h * d[i]) * Ft
        cnt.nf += 1
        u[i] = lu_solve(lu, rhs)
        cnt.nsolve += 1
    y_new = U + u[7]          # U is U_8 here (stage-8 argument)
    return y_new, u[7].copy(), H @ u


def rodas5p_dense(y0, y1, K, theta):
    th1 = 1.0 - theta
    return th1 * y0 + theta * (y1 + th1 * (K[0] + theta * (K[1] + theta * K[2])))


R23_D = 1.0 / (2.0 + math.sqrt(2.0))
R23_E32 = 6.0 + math.sqrt(2.0)


def ros23_step(f, jac, ft, t, y, h, cnt, use_ft=True, jac_override=None, F0=None):
    """One Rosenbrock23 (ode23s) step. Returns (y_new, err_est, (k1, k2), F2)."""
    d, e32 = R23_D, R23_E32
    n = y.size
    J = jac(t, y) if jac_override is None else jac_override(t, y)
    T = ft(t, y) if use_ft else np.zeros(n)
    cnt.njac += 1
    lu = lu_factor(np.eye(n) - (h * d) * J)
    cnt.nlu += 1
    if F0 is None:
        F0 = f(t, y)
        cnt.nf += 1
    k1 = lu_solve(lu, F0 + (h * d) * T)
    F1 = f(t + 0.5 * h, y + 0.5 * h * k1)
    k2 = lu_solve(lu, F1 - k1) + k1
    y_new = y + h * k2
    F2 = f(t + h, y_new)
    k3 = lu_solve(lu, F2 - e32 * (k2 - F1) - 2.0 * (k1 - F0) + (h * d) * T)
    cnt.nf += 2
    cnt.nsolve += 3
    err = (h / 6.0) * (k1 - 2.0 * k2 + k3)
    return y_new, err, (k1, k2), F2


def ros23_dense(y0, h, k1, k2, s):
    d = R23_D
    return y0 + h * (s * (1 - s) / (1 - 2 * d) * k1 + s * (s - 2 * d) / (1 - 2 * d) * k2)


# --------------------------------------------------------------------------
# Test problems with known solutions (non-autonomous)
# --------------------------------------------------------------------------

class Forced:
    """P1: y1' = y2, y2' = -y1 + cos t, y(0) = (1, 0) (linear, non-autonomous).
    Exact: y1 = cos t + (t/2) sin t, y2 = -(1/2) sin t + (t/2) cos t."""
    name = "P1 linear forced oscillator y1'=y2, y2'=-y1+cos t"

    @staticmethod
    def f(t, y):
        return np.array([y[1], -y[0] + math.cos(t)])

    @staticmethod
    def jac(t, y):
        return np.array([[0.0, 1.0], [-1.0, 0.0]])

    @staticmethod
    def ft(t, y):
        return np.array([0.0, -math.sin(t)])

    @staticmethod
    def exact(t):
        return np.array([math.cos(t) + 0.5 * t * math.sin(t),
                         -0.5 * math.sin(t) + 0.5 * t * math.cos(t)])


class Manufactured:
    """P2: y' = g(y) + phi'(t) - g(phi(t)), nonlinear g, exact solution phi.
    g(y) = (-y1^2 + y1 y2, -y2^3 + sin(y1)),
    phi(t) = (1 + 0.5 sin(2t), cos(t) exp(-t/2))."""
    name = "P2 nonlinear manufactured y'=g(y)+phi'(t)-g(phi(t))"

    @staticmethod
    def g(y):
        return np.array([-y[0] ** 2 + y[0] * y[1], -y[1] ** 3 + math.sin(y[0])])

    @staticmethod
    def gjac(y):
        return np.array([[-2 * y[0] + y[1], y[0]],
                         [math.cos(y[0]), -3 * y[1] ** 2]])

    @staticmethod
    def exact(t):
        return np.array([1 + 0.5 * math.sin(2 * t), math.cos(t) * math.exp(-0.5 * t)])

    @staticmethod
    def dexact(t):
        e = math.exp(-0.5 * t)
        return np.array([math.cos(2 * t), (-math.sin(t) - 0.5 * math.cos(t)) * e])

    @staticmethod
    def ddexact(t):
        e = math.exp(-0.5 * t)
        # d/dt[(-sin t - cos t/2) e^{-t/2}] = (-cos t + sin t/2) e - (1/2)(-sin t - cos t/2) e
        return np.array([-2 * math.sin(2 * t),
                         (-math.cos(t) + 0.5 * math.sin(t) + 0.5 * math.sin(t) + 0.25 * math.cos(t)) * e])

    @classmethod
    def f(cls, t, y):
        p = cls.exact(t)
        return cls.g(y) + cls.dexact(t) - cls.g(p)

    @classmethod
    def jac(cls, t, y):
        return cls.gjac(y)

    @classmethod
    def ft(cls, t, y):
        p = cls.exact(t)
        return cls.ddexact(t) - cls.gjac(p) @ cls.dexact(t)


def check_problem_derivatives(P):
    """Finite-difference check of the hand-written Jacobian and df/dt."""
    t, y = 0.37, P.exact(0.37) + np.array([0.013, -0.021])
    eps = 1e-6
    Jfd = np.column_stack([(P.f(t, y + eps * e) - P.f(t, y - eps * e)) / (2 * eps)
                           for e in np.eye(2)])
    ftfd = (P.f(t + eps, y) - P.f(t - eps, y)) / (2 * eps)
    return np.max(np.abs(Jfd - P.jac(t, y))), np.max(np.abs(ftfd - P.ft(t, y)))


# --------------------------------------------------------------------------
# (a) convergence orders, (c) dense output
# --------------------------------------------------------------------------

def fixed_step_solve(method, P, t0, t1, N, tab=None, **kw):
    h = (t1 - t0) / N
    y = P.exact(t0)
    t = t0
    cnt = Counter()
    for k in range(N):
        if method == "rodas5p":
            y = rodas5p_step(tab, P.f, P.jac, P.ft, t, y, h, cnt, **kw)[0]
        else:
            y = ros23_step(P.f, P.jac, P.ft, t, y, h, cnt, **kw)[0]
        t = t0 + (k + 1) * h
    return y


def orders_table(label, hs, errs):
    rows = []
    for k in range(len(hs)):
        o = "" if k == 0 else f"{math.log(errs[k - 1] / errs[k]) / math.log(hs[k - 1] / hs[k]):6.3f}"
        rows.append(f"    h={hs[k]:<10.5g} err={errs[k]:<11.4e} order={o}")
    print(f"  {label}")
    print("\n".join(rows))


def global_order_test(method, P, Ns, tab=None, t1=2.0, **kw):
    errs = [np.max(np.abs(fixed_step_solve(method, P, 0.0, t1, N, tab, **kw) - P.exact(t1)))
            for N in Ns]
    hs = [t1 / N for N in Ns]
    return hs, errs


def local_tests(method, P, hs, tab=None, t0=0.3, thetas=(0.25, 0.5, 0.75)):
    """Single step from the exact solution: local error, estimate, dense error."""
    y0 = P.exact(t0)
    out = {"local": [], "est": [], "emb": [], "dense": {th: [] for th in thetas}}
    for h in hs:
        cnt = Counter()
        if method == "rodas5p":
            y1, est, K = rodas5p_step(tab, P.f, P.jac, P.ft, t0, y0, h, cnt)
            dense = {th: rodas5p_dense(y0, y1, K, th) for th in thetas}
        else:
            y1, est, (k1, k2), _ = ros23_step(P.f, P.jac, P.ft, t0, y0, h, cnt)
            dense = {th: ros23_dense(y0, h, k1, k2, th) for th in thetas}
        ex = P.exact(t0 + h)
        out["local"].append(np.max(np.abs(y1 - ex)))
        out["est"].append(np.max(np.abs(est)))
        # Companion solution: Rodas5P est = u_8 = y_new - U_8, so U_8 = y_new - est (order 4);
        # Rosenbrock23 est = h/6(k1-2k2+k3) = y3 - y_new with the order-3
        # y3 = y + h/6(k1+4k2+k3), so y3 = y_new + est.
        comp = y1 - est if method == "rodas5p" else y1 + est
        out["emb"].append(np.max(np.abs(comp - ex)))
        for th in thetas:
            out["dense"][th].append(np.max(np.abs(dense[th] - P.exact(t0 + th * h))))
    return out


def dense_global_test(method, P, Ns, tab=None, t1=2.0):
    """Fixed-step run; max error of the interpolant at theta=0.5 over all steps."""
    res = []
    for N in Ns:
        h = t1 / N
        y = P.exact(0.0)
        emax = 0.0
        for k in range(N):
            t = k * h
            cnt = Counter()
            if method == "rodas5p":
                y1, _, K = rodas5p_step(tab, P.f, P.jac, P.ft, t, y, h, cnt)
                ym = rodas5p_dense(y, y1, K, 0.5)
            else:
                y1, _, (k1, k2), _ = ros23_step(P.f, P.jac, P.ft, t, y, h, cnt)
                ym = ros23_dense(y, h, k1, k2, 0.5)
            emax = max(emax, np.max(np.abs(ym - P.exact(t + 0.5 * h))))
            y = y1
        res.append(emax)
    return [t1 / N for N in Ns], res


# --------------------------------------------------------------------------
# (b) Robertson with a simple adaptive controller
# --------------------------------------------------------------------------

K1, K2, K3 = 0.04, 3.0e7, 1.0e4


def rober_f(t, y):
    return np.array([-K1 * y[0] + K3 * y[1] * y[2],
                     K1 * y[0] - K3 * y[1] * y[2] - K2 * y[1] ** 2,
                     K2 * y[1] ** 2])


def rober_jac(t, y):
    return np.array([[-K1, K3 * y[2], K3 * y[1]],
                     [K1, -K3 * y[2] - 2 * K2 * y[1], -K3 * y[1]],
                     [0.0, 2 * K2 * y[1], 0.0]])


def rober_ft(t, y):
    return np.zeros(3)


def adaptive(method, tab, f, jac, ft, t0, y0, tf, rtol, atol, h0, q):
    """Controller: err = RMS(e_i / (atol + rtol max(|y_i|, |ynew_i|)));
    accept iff err <= 1; h *= clip(0.9 err^(-1/(q+1)), 0.2, 6) (after a
    rejection the factor is additionally capped at 1)."""
    t, y, h = t0, np.array(y0, dtype=float), h0
    cnt = Counter()
    nacc = nrej = 0
    F0 = None
    last_rejected = False
    while t < tf:
        if t + h > tf:
            h = tf - t
        if method == "rodas5p":
            ynew, est, _ = rodas5p_step(tab, f, jac, ft, t, y, h, cnt)
            F2 = None
        else:
            ynew, est, _, F2 = ros23_step(f, jac, ft, t, y, h, cnt, F0=F0)
        sc = atol + rtol * np.maximum(np.abs(y), np.abs(ynew))
        err = math.sqrt(np.mean((est / sc) ** 2))
        if not np.isfinite(err):
            err = 1e10
        fac = 6.0 if err == 0.0 else min(6.0, max(0.2, 0.9 * err ** (-1.0 / (q + 1))))
        if err <= 1.0:
            t += h
            y = ynew
            nacc += 1
            F0 = F2  # FSAL for Rosenbrock23 (F2 = f(t+h, ynew))
            if last_rejected:
                fac = min(fac, 1.0)
            last_rejected = False
        else:
            nrej += 1
            fac = min(fac, 1.0)
            last_rejected = True
        h *= fac
    return y, nacc, nrej, cnt


# --------------------------------------------------------------------------
# Linear stability function R(z) from one step of y' = lambda y, z = h lambda
# --------------------------------------------------------------------------

def stability_checks(tab):
    print("== Linear stability function R(z) (one step of y'=lambda*y, y0=1, h=1) ==")
    for name in ("Rodas5P", "Rosenbrock23"):
        def R(z):
            f = lambda t, y: z * y
            jac = lambda t, y: np.array([[z]], dtype=complex)
            ft = lambda t, y: np.zeros(1, dtype=complex)
            y0 = np.ones(1, dtype=complex)
            if name == "Rodas5P":
                return rodas5p_step(tab, f, jac, ft, 0.0, y0, 1.0, Counter())[0][0]
            return ros23_step(f, jac, ft, 0.0, y0, 1.0, Counter())[0][0]
        w = np.concatenate([-np.logspace(-3, 8, 400), [0.0], np.logspace(-3, 8, 400)])
        imax = max(abs(R(1j * x)) for x in w)
        lhp = max(abs(R(complex(-10 ** a, 10 ** b))) for a in np.linspace(-3, 6, 40)
                  for b in np.linspace(-3, 6, 40))
        print(f"  {name}: |R(-1e12)| = {abs(R(-1e12)):.2e}, |R(-1e4)| = {abs(R(-1e4)):.2e}, "
              f"max|R(i w)| on grid = {imax:.12f}, max|R| on LHP grid = {lhp:.6f}, "
              f"R(-0.1) - exp(-0.1) = {abs(R(-0.1) - math.exp(-0.1)):.2e}")
    print()


# --------------------------------------------------------------------------
# Extra: stale/approximate Jacobian (W-method behaviour), informative only
# --------------------------------------------------------------------------

def perturbed_jac(P, delta=0.3):
    def jo(t, y):
        return P.jac(t, y) + delta * np.array([[1.0, -0.5], [0.25, 1.0]])
    return jo


# --------------------------------------------------------------------------

def main():
    print(f"python {sys.version.split()[0]}, numpy {np.__version__}, scipy {scipy.__version__}")
    tab, literals = load_rodas5p()
    ok = check_tableau(tab, literals)
    print()

    stability_checks(tab)

    problems = [Forced, Manufactured]
    print("== Problem derivative checks (central FD vs analytic) ==")
    for P in problems:
        ej, et = check_problem_derivatives(P)
        print(f"  {P.name}: max|J-J_fd|={ej:.1e}, max|f_t-f_t,fd|={et:.1e}")
    print()

    # (a) global orders
    print("== (a) Global convergence at t=2 (fixed step, max-norm error) ==")
    for P in problems:
        print(f" {P.name}")
        Ns = [10, 20, 40, 80, 160] if P is Forced else [10, 20, 40, 80, 160, 320]
        hs, e = global_order_test("rodas5p", P, Ns, tab)
        orders_table("Rodas5P (expect 5)", hs, e)
        hs, e = global_order_test("ros23", P, [20, 40, 80, 160, 320, 640])
        orders_table("Rosenbrock23 (expect 2)", hs, e)
    print()
    print("  Control: same runs with the df/dt terms switched off (shows they are exercised)")
    hs, e = global_order_test("rodas5p", Manufactured, [10, 20, 40, 80, 160], tab, use_ft=False)
    orders_table("Rodas5P on P2 without d_i*h*f_t", hs, e)
    hs, e = global_order_test("ros23", Manufactured, [20, 40, 80, 160, 320, 640], use_ft=False)
    orders_table("Rosenbrock23 on P2 without h*d*T", hs, e)
    print()

    # (a') local error, error estimate and (c) dense output
    print("== (a') Local errors of one step from the exact solution at t0=0.3 ==")
    print("   slope = log-log slope vs h; expected: local err h^(p+1), estimate h^(q+1),")
    print("   dense err h^(p_dense+1)")
    hs = [0.4 / 2 ** k for k in range(6)]
    for P in problems:
        print(f" {P.name}")
        r = local_tests("rodas5p", P, hs, tab)
        orders_table("Rodas5P local error of y_new (expect 6)", hs, r["local"])
        orders_table("Rodas5P error estimate |u_8| (expect 5)", hs, r["est"])
        orders_table("Rodas5P local error of embedded U_8 (expect 5)", hs, r["emb"])
        for th in (0.25, 0.5, 0.75):
            orders_table(f"Rodas5P dense output theta={th} (expect 5)", hs, r["dense"][th])
        hs2 = [0.2 / 2 ** k for k in range(6)]
        r = local_tests("ros23", P, hs2)
        orders_table("Rosenbrock23 local error of y_new (expect 3)", hs2, r["local"])
        orders_table("Rosenbrock23 error estimate h/6|k1-2k2+k3| (expect 3)", hs2, r["est"])
        orders_table("Rosenbrock23 local error of y_new + est = y+h/6(k1+4k2+k3) (expect 4)",
                     hs2, r["emb"])
        for th in (0.25, 0.5, 0.75):
            orders_table(f"Rosenbrock23 interpolant theta={th} (expect 3)", hs2, r["dense"][th])
    print()
    print("== (c') Dense output along a fixed-step run on P2 (max over steps, theta=0.5) ==")
    hs, e = dense_global_test("rodas5p", Manufactured, [10, 20, 40, 80, 160], tab)
    orders_table("Rodas5P interpolant (global; expect 4 or better)", hs, e)
    hs, e = dense_global_test("ros23", Manufactured, [20, 40, 80, 160, 320, 640])
    orders_table("Rosenbrock23 interpolant (global; expect 2)", hs, e)
    print()

    print("== Extra: approximate Jacobian J + 0.3*E (W-method behaviour), P2 ==")
    jo = perturbed_jac(Manufactured)
    hs, e = global_order_test("ros23", Manufactured, [20, 40, 80, 160, 320, 640], jac_override=jo)
    orders_table("Rosenbrock23 with inexact J", hs, e)
    hs, e = global_order_test("rodas5p", Manufactured, [10, 20, 40, 80, 160], tab, jac_override=jo)
    orders_table("Rodas5P with inexact J (not a W-method: order should drop)", hs, e)
    print()

    # (b) Robertson
    print("== (b) Robertson k1=0.04 k2=3e7 k3=1e4, y0=(1,0,0), t in [0, 1e5] ==")
    y0 = np.array([1.0, 0.0, 0.0])
    tf = 1.0e5
    t_s = time.time()
    ref = solve_ivp(rober_f, (0.0, tf), y0, method="Radau", rtol=1e-12, atol=1e-14,
                    jac=rober_jac)
    yref = ref.y[:, -1]
    print(f"  SciPy Radau rtol=1e-12 atol=1e-14: status={ref.status}, nsteps={ref.t.size - 1}, "
          f"nfev={ref.nfev}, njev={ref.njev}, nlu={ref.nlu}, {time.time() - t_s:.1f}s")
    print(f"    y_ref(1e5) = [{yref[0]:.15e}, {yref[1]:.15e}, {yref[2]:.15e}]")
    ref2 = solve_ivp(rober_f, (0.0, tf), y0, method="Radau", rtol=1e-13, atol=1e-16,
                     jac=rober_jac).y[:, -1]
    print("    reference self-check vs Radau rtol=1e-13 atol=1e-16: rel. diff = "
          + ", ".join(f"{v:.1e}" for v in np.abs(yref - ref2) / np.abs(ref2)))
    rtol, atol = 1e-6, 1e-10
    for method, q in (("rodas5p", 4), ("ros23", 2)):
        t_s = time.time()
        y, nacc, nrej, cnt = adaptive(method, tab, rober_f, rober_jac, rober_ft, 0.0, y0, tf,
                                      rtol, atol, 1e-6, q)
        name = "Rodas5P" if method == "rodas5p" else "Rosenbrock23"
        relerr = np.abs(y - yref) / np.abs(yref)
        scaled = np.abs(y - yref) / (atol + rtol * np.abs(yref))
        print(f"  {name} (q={q}, factor 0.9*err^(-1/{q + 1}) in [0.2,6], rtol={rtol}, atol={atol}, h0=1e-6):")
        print(f"    accepted={nacc}, rejected={nrej}, f-evals={cnt.nf}, LU={cnt.nlu}, "
              f"{time.time() - t_s:.1f}s")
        print(f"    y(1e5)     = [{y[0]:.15e}, {y[1]:.15e}, {y[2]:.15e}]")
        print(f"    |y-yref|   = [{abs(y[0]-yref[0]):.3e}, {abs(y[1]-yref[1]):.3e}, {abs(y[2]-yref[2]):.3e}]")
        print(f"    rel. error = [{relerr[0]:.3e}, {relerr[1]:.3e}, {relerr[2]:.3e}]")
        print(f"    |y-yref|/(atol+rtol|yref|) = [{scaled[0]:.3f}, {scaled[1]:.3f}, {scaled[2]:.3f}]")
        print(f"    mass conservation |sum(y)-1| = {abs(y.sum() - 1):.2e}")
    print()
    print("tableau checks passed" if ok else "TABLEAU CHECKS FAILED")


if __name__ == "__main__":
    main()
