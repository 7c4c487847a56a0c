//! Butcher tableau of Tsit5: Tsitouras' 7-stage, FSAL explicit Runge–Kutta pair of order 5(4),
//! with its free continuous extension of order 4 (dense output).
//!
//! Source: Ch. Tsitouras, "Runge–Kutta pairs of order 5(4) satisfying only the first column
//! simplifying assumption", Computers & Mathematics with Applications 62 (2011) 770–775,
//! doi:10.1016/j.camwa.2011.06.002, where the coefficients are listed as decimals. Every literal
//! below is the correctly rounded `f64` of the 85-digit values of the same tableau in
//! OrdinaryDiffEq.jl (`lib/OrdinaryDiffEqTsit5/src/tsit_tableaus.jl`, the BigFloat method of
//! `Tsit5ConstantCacheActual`), which satisfy the order conditions to 1e-60. The dense output is
//! described at [`DENSE`]. Literals are written in shortest round-trip form.
//!
//! One step of size h from (t₀, y₀), i = 1..7:
//!
//! ```text
//! k_i = f(t₀ + C[i-1]·h, y₀ + h·Σ_{j<i} A[i-1][j-1]·k_j)
//! y₁  = y₀ + h·Σ_i B[i-1]·k_i                      (order 5, the solution that is propagated)
//! ŷ₁  = y₀ + h·Σ_i (B[i-1] − BTILDE[i-1])·k_i      (order 4, embedded)
//! err = y₁ − ŷ₁ = h·Σ_i BTILDE[i-1]·k_i
//! ```
//!
//! Row 7 of A equals B and `C[6]` = 1, so the 7th stage is k₇ = f(t₀ + h, y₁): it is the next
//! step's k₁ (first same as last) and a step costs 6 new evaluations of f. `B[6]` = 0. The error is
//! O(h⁵), so a step-size controller uses the exponent 1/5.
//!
//! Checked by `check_tableaux.py`: every order condition (rooted tree) of order ≤ 5 for B, of
//! order ≤ 4 for B − BTILDE (and not 5), of order ≤ 4 for the dense weights at every θ tested;
//! and fixed-step runs with observed orders 5 (global), 6 (local), 5 (dense local error).

/// Number of stages; the last is f(t₀ + h, y₁) and is reused as the next step's first.
pub(in crate::integrators) const STAGES: usize = 7;

/// Nodes c₁..c₇: stage i is evaluated at t₀ + `C[i-1]`·h (c₁ = 0, c₂ = 0.161, c₃ = 0.327,
/// c₄ = 0.9, c₅ = 0.98002554…, c₆ = c₇ = 1).
pub(in crate::integrators) const C: [f64; 7] =
    [0.0, 0.161, 0.327, 0.9, 0.9800255409045097, 1.0, 1.0];

/// Coupling coefficients, `A[i-1][j-1]` = a_ij for j < i (strictly lower triangular: entries on and
/// above the diagonal are 0). Row 1 is all zero; row 7 equals [`B`] (FSAL).
pub(in crate::integrators) const A: [[f64; 7]; 7] = [
    // stage 1
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    // stage 2
    [0.161, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    // stage 3
    [
        -0.008480655492356989,
        0.335480655492357,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    // stage 4
    [
        2.8971530571054935,
        -6.359448489975075,
        4.3622954328695815,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    // stage 5
    [
        5.325864828439257,
        -11.748883564062828,
        7.4955393428898365,
        -0.09249506636175525,
        0.0,
        0.0,
        0.0,
    ],
    // stage 6
    [
        5.86145544294642,
        -12.92096931784711,
        8.159367898576159,
        -0.071584973281401,
        -0.028269050394068383,
        0.0,
        0.0,
    ],
    // stage 7
    [
        0.09646076681806523,
        0.01,
        0.4798896504144996,
        1.379008574103742,
        -3.290069515436081,
        2.324710524099774,
        0.0,
    ],
];

/// Weights b₁..b₇ of the 5th-order solution y₁ (= row 7 of [`A`]; b₇ = 0).
pub(in crate::integrators) const B: [f64; 7] = [
    0.09646076681806523,
    0.01,
    0.4798896504144996,
    1.379008574103742,
    -3.290069515436081,
    2.324710524099774,
    0.0,
];

/// Error weights BTILDE = b − b̂ (5th-order minus embedded 4th-order weights), so that
/// y₁ − ŷ₁ = h·Σ_i `BTILDE[i-1]`·k_i; they sum to 0 and `BTILDE[6]` = −1/66 (b̂₇ = 1/66).
///
/// Sign: OrdinaryDiffEq.jl stores the opposite, `btilde = b̂ − b` (its btilde7 = +1/66).
/// According to OrdinaryDiffEq.jl issue #1654, diffrax issue #98 and SUNDIALS PR #850, the
/// paper's Table 1 lists these differences where b̂ is expected, the last one with the wrong
/// sign. The sign only matters if the signed error is used; its norm is the same either way.
/// b̂ = B − BTILDE (order 4, checked) is
/// 0.0946807557658394…, 0.0091835655403432…, 0.4877705284247615…, 1.2342975669304789…,
/// −2.7077123499835254…, 1.8666284181705870…, 1/66.
pub(in crate::integrators) const BTILDE: [f64; 7] = [
    0.0017800110522257714,
    0.0008164344596567469,
    -0.007880878010261995,
    0.1447110071732629,
    -0.5823571654525552,
    0.45808210592918697,
    -0.015151515151515152,
];

/// Dense output: for θ in [0, 1], measured from the start of the step (t = t₀ + θ·h),
///
/// ```text
/// u(t₀ + θ·h) = y₀ + h·Σ_i b_i(θ)·k_i
/// b_i(θ)      = θ·(R[0] + θ·(R[1] + θ·(R[2] + θ·R[3]))),   R = DENSE[i-1]
/// ```
///
/// so `DENSE[i-1][m]` is the coefficient of θ^(m+1) in b_i(θ) (OrdinaryDiffEq.jl's r_{i,m+1}).
/// It uses only the 7 stages of the step. Order 4 for every θ; b(1) = B, so u(t₀ + h) = y₁;
/// b'(0) = e₁ and b'(1) = e₇, so u' equals f at both ends and u is C¹ across steps.
///
/// The paper gives the b_i(θ) in factored form with 17–19-digit decimals (e.g.
/// b₇(θ) = 2.5·θ²·(θ − 1)·(θ − 0.6), b₂(θ) = 0.1017·θ²·(θ² − 2.19665…·θ + 1.29498…), i.e.
/// θ²·(0.1317 − 0.2234·θ + 0.1017·θ²)). The properties above leave one free parameter; the
/// paper's r₂₄ = 0.1017 fixes it. These literals are the correctly rounded `f64` of the unique
/// polynomials so defined, solved at 60 digits from the 85-digit tableau; they agree with every
/// digit the paper prints (relative difference ≤ 4e-17), and with OrdinaryDiffEq.jl's `Float64`
/// r's to 1 ulp (r₂₂ = 0.1317 here, 0.13169999999999998 there).
pub(in crate::integrators) const DENSE: [[f64; 4]; 7] = [
    // b_1(θ)
    [
        1.0,
        -2.763706197274826,
        2.9132554618219126,
        -1.0530884977290216,
    ],
    // b_2(θ)
    [0.0, 0.1317, -0.2234, 0.1017],
    // b_3(θ)
    [
        0.0,
        3.9302962368947516,
        -5.941033872131505,
        2.490627285651253,
    ],
    // b_4(θ)
    [
        0.0,
        -12.411077166933676,
        30.33818863028232,
        -16.548102889244902,
    ],
    // b_5(θ)
    [0.0, 37.50931341651104, -88.1789048947664, 47.37952196281928],
    // b_6(θ)
    [
        0.0,
        -27.896526289197286,
        65.09189467479366,
        -34.87065786149661,
    ],
    // b_7(θ)
    [0.0, 1.5, -4.0, 2.5],
];
