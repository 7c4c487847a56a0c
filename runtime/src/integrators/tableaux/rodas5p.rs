//! Coefficients of Rodas5P, an 8-stage, stiffly accurate Rosenbrock–Wanner
//! method of order 5 with an embedded order-4 solution and an order-4 dense
//! output.
//!
//! # Source
//!
//! G. Steinebach, "Construction of Rosenbrock–Wanner method Rodas5P and
//! numerical benchmarks within the Julia Differential Equations package",
//! BIT Numerical Mathematics 63 (2023), article 27,
//! <https://doi.org/10.1007/s10543-023-00967-x>.
//!
//! The paper states the method in the classical ROW form (its eqs. (1.2)–(1.3)):
//!
//! ```text
//! (M − h γ f_y) k_i = h f(t0 + α_i h, y0 + Σ_j α_ij k_j) + h f_y Σ_j γ_ij k_j + h² γ_i f_t
//! y1 = y0 + Σ_i b_i k_i
//! ```
//!
//! The numbers below are the *transformed* ("W-transformed"; Hairer & Wanner,
//! Solving ODEs II, §IV.7, eq. (7.4')) coefficients of the same method. They
//! were read from the
//! MIT-licensed Julia package OrdinaryDiffEq.jl, sub-package
//! `OrdinaryDiffEqRosenbrock`, file `src/rosenbrock_tableaus.jl`, function
//! `Rodas5PTableau` (repository `SciML/OrdinaryDiffEq.jl`, path
//! `lib/OrdinaryDiffEqRosenbrock/src/rosenbrock_tableaus.jl`, commit
//! `1d7f56b77b48ca703d2459d54ff9b93a07a1ca2a`). An older scalar-per-field copy of
//! the same tableau (`a21 = …`, `C21 = …`, `h21 = …`) has identical digits.
//! The step and dense-output conventions were read from
//! `lib/OrdinaryDiffEqRosenbrock/src/rosenbrock_perform_step.jl` and
//! `lib/OrdinaryDiffEqRosenbrock/src/rosenbrock_interpolants.jl` of the same
//! repository. Only numbers were taken, never code.
//!
//! The transformed quantities relate to the paper's by `Γ = (γ_ij)` (with
//! `γ_ii = γ`), `(a_ij) = (α_ij) Γ⁻¹`, `(C_ij) = γ⁻¹ I − Γ⁻¹`, `c_i = α_i = Σ_j α_ij`,
//! `d_i = γ_i = Σ_{j≤i} γ_ij`, and stage increments `u_i = Σ_j γ_ij k_j`.
//! `scripts/check_rosenbrock.py` recovers `α` and `Γ` from `a`, `C`, `γ`, checks that their row
//! sums reproduce `c` and `d` to rounding, and measures the orders in plain Python.
//!
//! # One step from `(t, y)` with step `h` (identity mass matrix)
//!
//! `J = ∂f/∂y(t, y)`, `f_t = ∂f/∂t(t, y)`, both taken once per step at the start
//! point. All eight stages share one matrix `W = I/(h γ) − J`. Note the sign:
//! this is `I/(hγ) − J`, so `γ` **divides** `I`. (Multiplying by `hγ` gives the
//! equivalent `(I − hγJ) u_i = hγ · rhs_i`.) For `i = 1, …, 8` (0-based index
//! `i-1` in the arrays below):
//!
//! ```text
//! U_i  = y + Σ_{j<i} a_ij u_j                      (stage value; U_1 = y)
//! rhs_i = f(t + c_i h, U_i) + Σ_{j<i} (C_ij / h) u_j + h d_i f_t
//! (I/(h γ) − J) u_i = rhs_i                        (solve for u_i)
//! ```
//!
//! The `C` term enters with a **plus** sign and `C_ij` is **divided** by `h`;
//! `d_i` is **multiplied** by `h`. The `u_i` are solution increments (they have
//! the units of `y`, not of `y'`).
//!
//! With a constant mass matrix `M`:
//!
//! ```text
//! (M/(hγ) − J) u_i = f(t + c_i h, U_i) + M Σ_{j<i} (C_ij/h) u_j + h d_i f_t
//! ```
//!
//! # New solution and error estimate (stiffly accurate)
//!
//! Rows 7 and 8 of `a` are row 6 with trailing ones (`a_76 = 1`, `a_86 = a_87 = 1`),
//! so `U_7 = U_6 + u_6` and `U_8 = U_7 + u_7`. `c_6 = c_7 = c_8 = 1` and
//! `d_6 = d_7 = d_8 = 0`.
//!
//! ```text
//! y_{n+1} = U_8 + u_8            (order 5; equals y + Σ_{j<8} a_8j u_j + u_8)
//! ŷ_{n+1} = U_8                  (embedded, order 4)
//! err     = y_{n+1} − ŷ_{n+1} = u_8
//! ```
//!
//! The estimate `u_8` is `O(h^5)` (it measures the local error of the order-4
//! solution), so a step-size controller uses exponent `1/5`.
//!
//! # Dense output (order 4)
//!
//! After the step, form three vectors from the stage increments
//!
//! ```text
//! K_r = Σ_{j=1..8} H_rj u_j,   r = 1, 2, 3   (no factor h: u_j already carry it)
//! ```
//!
//! and for `θ ∈ [0, 1]`
//!
//! ```text
//! y(t + θh) ≈ (1 − θ) y_n + θ ( y_{n+1} + (1 − θ) ( K_1 + θ ( K_2 + θ K_3 ) ) )
//! ```
//!
//! which reproduces `y_n` at `θ = 0` and `y_{n+1}` at `θ = 1`. Its derivative
//! is `( K_1 + θ(−2K_1 + 2K_2 + θ(−3K_2 + 3K_3 − 4θ K_3)) − y_n + y_{n+1} ) / h`.

/// Number of stages of Rodas5P.
pub(in crate::integrators) const STAGES: usize = 8;

/// Diagonal coefficient `γ` (gamma): the stage matrix is `I/(h γ) − J`.
pub(in crate::integrators) const GAMMA: f64 = 0.21193756319429014;

/// Transformed stage-value coefficients `a_ij` (strictly lower triangular,
/// `A[i][j]` is `a_{i+1, j+1}`; entries with `j ≥ i` are zero):
/// `U_i = y + Σ_{j<i} a_ij u_j`. Rows 7 and 8 equal row 6 extended by ones,
/// which makes the method stiffly accurate.
pub(in crate::integrators) const A: [[f64; 8]; 8] = [
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [
        2.849394379747939,
        0.45842242204463923,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        -6.954028509809101,
        2.489845061869568,
        -10.358996098473584,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        2.8029986275628964,
        0.5072464736228206,
        -0.3988312541770524,
        -0.04721187230404641,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        -7.502846399306121,
        2.561846144803919,
        -11.627539656261098,
        -0.18268767659942256,
        0.030198172008377946,
        0.0,
        0.0,
        0.0,
    ],
    [
        -7.502846399306121,
        2.561846144803919,
        -11.627539656261098,
        -0.18268767659942256,
        0.030198172008377946,
        1.0,
        0.0,
        0.0,
    ],
    [
        -7.502846399306121,
        2.561846144803919,
        -11.627539656261098,
        -0.18268767659942256,
        0.030198172008377946,
        1.0,
        1.0,
        0.0,
    ],
];

/// Transformed coupling coefficients `C_ij` (strictly lower triangular,
/// `COUPLING[i][j]` is `C_{i+1, j+1}`; entries with `j ≥ i` are zero). They
/// enter stage `i` as `+ Σ_{j<i} (C_ij / h) u_j` on the right-hand side.
pub(in crate::integrators) const COUPLING: [[f64; 8]; 8] = [
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [-14.155112264123755, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [
        -17.97296035885952,
        -2.859693295451294,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        147.12150275711716,
        -1.41221402718213,
        71.68940251302358,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        165.43517024871676,
        -0.4592823456491126,
        42.90938336958603,
        -5.961986721573306,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        24.854864614690072,
        -3.0009227002832186,
        47.4931110020768,
        5.5814197821558125,
        -0.6610691825249471,
        0.0,
        0.0,
        0.0,
    ],
    [
        30.91273214028599,
        -3.1208243349937974,
        77.79954646070892,
        34.28646028294783,
        -19.097331116725623,
        -28.087943162872662,
        0.0,
        0.0,
    ],
    [
        37.80277123390563,
        -3.2571969029072276,
        112.26918849496327,
        66.9347231244047,
        -40.06618937091002,
        -54.66780262877968,
        -9.48861652309627,
        0.0,
    ],
];

/// Stage times `c_i` (the paper's `α_i = Σ_j α_ij`): stage `i` evaluates
/// `f` at `t + c_i h`. `c_2 = 3γ`; the last three stages sit at `t + h`.
pub(in crate::integrators) const C: [f64; 8] = [
    0.0,
    0.6358126895828704,
    0.4095798393397535,
    0.9769306725060716,
    0.4288403609558664,
    1.0,
    1.0,
    1.0,
];

/// Time-derivative coefficients `d_i` (the paper's `γ_i = Σ_{j≤i} γ_ij`):
/// stage `i` adds `+ h d_i ∂f/∂t(t, y)` to its right-hand side.
/// `d_1 = γ`, `d_2 = −2γ`, and `d_6 = d_7 = d_8 = 0`.
pub(in crate::integrators) const D: [f64; 8] = [
    0.21193756319429014,
    -0.42387512638858027,
    -0.3384627126235924,
    1.8046452872882734,
    2.325825639765069,
    0.0,
    0.0,
    0.0,
];

/// Dense-output coefficients: `K_r = Σ_j H[r][j] u_j` for `r = 0, 1, 2`
/// (the `K_1, K_2, K_3` of the module docs), used in
/// `y(t + θh) ≈ (1−θ) y_n + θ (y_{n+1} + (1−θ)(K_1 + θ(K_2 + θ K_3)))`.
pub(in crate::integrators) const H: [[f64; 8]; 3] = [
    [
        25.948786856663858,
        -2.5579724845846235,
        10.433815404888879,
        -2.3679251022685204,
        0.524948541321073,
        1.1241088310450404,
        0.4272876194431874,
        -0.17202221070155493,
    ],
    [
        -9.91568850695171,
        -0.9689944594115154,
        3.0438037242978453,
        -24.495224566215796,
        20.176138334709044,
        15.98066361424651,
        -6.789040303419874,
        -6.710236069923372,
    ],
    [
        11.419903575922262,
        2.8879645146136994,
        72.92137995996029,
        80.12511834622643,
        -52.072871366152654,
        -59.78993625266729,
        -0.15582684282751913,
        4.883087185713722,
    ],
];
