//! Butcher tableau of DOP853: the explicit Runge–Kutta method of order 8 by Dormand and Prince
//! (12 stages), with Hairer and Wanner's "8(5,3)" error estimate and a dense output of order 7
//! that costs 3 extra stages, exactly as in the Fortran code DOP853.
//!
//! Sources: E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I:
//! Nonstiff Problems*, 2nd ed., Springer 1993 (§II.5 explicit methods of higher order, §II.6
//! dense output, §II.10 the code DOP853 and its error estimate; the code's header points to this
//! book and, for the coefficients, to its Section II.6); and Hairer's code `dop853.f` (E. Hairer
//! and G. Wanner, version of April 25, 1996 with small corrections of March 4, 2002; the version
//! of October 11, 2009 has identical coefficients), distributed at
//! <http://www.unige.ch/~hairer/software.html>. Every literal below is the correctly rounded
//! `f64` of the 30-digit value in that code's PARAMETER statements (for E3, of B − bhh formed
//! from the 30-digit values), written in shortest round-trip form. SciPy's
//! `scipy/integrate/_ivp/dop853_coefficients.py` is a port of the same numbers and agrees bit
//! for bit (its E3 within 1 ulp, as it subtracts in `f64`).
//!
//! Stage numbering follows the code: stages 1–12 make the step, stage 13 is
//! k₁₃ = f(t₀ + h, y₁) (the next step's k₁, so a step costs 12 new evaluations) and stages 14–16
//! are evaluated only when the dense output is wanted. One step of size h from (t₀, y₀):
//!
//! ```text
//! k_i = f(t₀ + C[i-1]·h, y₀ + h·Σ_{j<i} A[i-1][j-1]·k_j),   i = 1..12
//! y₁  = y₀ + h·Σ_i B[i-1]·k_i                                (order 8)
//! ```
//!
//! Error estimate (dop853.f, DP86CO; N components, m = 1..N):
//!
//! ```text
//! sk_m   = atol_m + rtol_m·max(|y₀_m|, |y₁_m|)
//! err5_m = Σ_i E5[i-1]·k_i,m       err3_m = Σ_i E3[i-1]·k_i,m       (no factor h here)
//! ERR    = Σ_m (err5_m/sk_m)²      ERR2   = Σ_m (err3_m/sk_m)²
//! DENO   = ERR + 0.01·ERR2         (DENO = 1 if DENO ≤ 0)
//! err    = |h|·ERR/sqrt(N·DENO)
//! ```
//!
//! that is err = ‖e5‖² / sqrt(‖e5‖² + 0.01·‖e3‖²) with e5 = h·Σ E5·k, e3 = h·Σ E3·k and the RMS
//! norm ‖e‖² = (1/N)·Σ_m (e_m/sk_m)². The step is accepted when err ≤ 1. Since e5 = O(h⁶) and
//! e3 = O(h⁴), err = O(h⁸) as h → 0 (the code's controller uses the exponent 1/8:
//! h_new = h / clamp(err^(1/8)/0.9, 1/6, 1/0.333) after an accepted step, with its default
//! β = 0).
//!
//! Checked by `check_tableaux.py`: every order condition (rooted tree) of order ≤ 8 for B (and
//! not 9), of order ≤ 5 for B − E5, ≤ 3 for B − E3, ≤ 7 for the dense output at every θ tested;
//! fixed-step runs with observed orders 8 (global), 9 (local), 8 (dense local error).

/// Number of stages of a step (without the FSAL stage 13 and the dense-output stages 14–16).
pub(in crate::integrators) const STAGES: usize = 12;

/// Nodes c₁..c₁₂: stage i is evaluated at t₀ + `C[i-1]`·h (c₁ = 0, c₁₂ = 1). Stage 13, at c = 1,
/// is f(t₀ + h, y₁).
pub(in crate::integrators) const C: [f64; 12] = [
    0.0,
    0.05260015195876773,
    0.0789002279381516,
    0.1183503419072274,
    0.2816496580927726,
    0.3333333333333333,
    0.25,
    0.3076923076923077,
    0.6512820512820513,
    0.6,
    0.8571428571428571,
    1.0,
];

/// Coupling coefficients, `A[i-1][j-1]` = a_ij for j < i (strictly lower triangular). Many are 0:
/// a_i2 = 0 for i ≥ 4 and a_i3 = 0 for i ≥ 6, so rows 6–12 use column 1 and columns 4 onwards
/// (dop853.f skips these zeros).
pub(in crate::integrators) const A: [[f64; 12]; 12] = [
    // stage 1
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    // stage 2
    [
        0.05260015195876773,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    // stage 3
    [
        0.0197250569845379,
        0.0591751709536137,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    // stage 4
    [
        0.02958758547680685,
        0.0,
        0.08876275643042054,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    // stage 5
    [
        0.2413651341592667,
        0.0,
        -0.8845494793282861,
        0.924834003261792,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    // stage 6
    [
        0.037037037037037035,
        0.0,
        0.0,
        0.17082860872947386,
        0.12546768756682242,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    // stage 7
    [
        0.037109375,
        0.0,
        0.0,
        0.17025221101954405,
        0.06021653898045596,
        -0.017578125,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    // stage 8
    [
        0.03709200011850479,
        0.0,
        0.0,
        0.17038392571223998,
        0.10726203044637328,
        -0.015319437748624402,
        0.008273789163814023,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    // stage 9
    [
        0.6241109587160757,
        0.0,
        0.0,
        -3.3608926294469414,
        -0.868219346841726,
        27.59209969944671,
        20.154067550477894,
        -43.48988418106996,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    // stage 10
    [
        0.47766253643826434,
        0.0,
        0.0,
        -2.4881146199716677,
        -0.590290826836843,
        21.230051448181193,
        15.279233632882423,
        -33.28821096898486,
        -0.020331201708508627,
        0.0,
        0.0,
        0.0,
    ],
    // stage 11
    [
        -0.9371424300859873,
        0.0,
        0.0,
        5.186372428844064,
        1.0914373489967295,
        -8.149787010746927,
        -18.52006565999696,
        22.739487099350505,
        2.4936055526796523,
        -3.0467644718982196,
        0.0,
        0.0,
    ],
    // stage 12
    [
        2.273310147516538,
        0.0,
        0.0,
        -10.53449546673725,
        -2.0008720582248625,
        -17.9589318631188,
        27.94888452941996,
        -2.8589982771350235,
        -8.87285693353063,
        12.360567175794303,
        0.6433927460157636,
        0.0,
    ],
];

/// Weights b₁..b₁₂ of the 8th-order solution y₁ (b₂ … b₅ = 0). In the extended method they are
/// the coefficients of stage 13: k₁₃ = f(t₀ + h, y₀ + h·Σ `B[j-1]`·k_j) = f(t₀ + h, y₁).
pub(in crate::integrators) const B: [f64; 12] = [
    0.054293734116568765,
    0.0,
    0.0,
    0.0,
    0.0,
    4.450312892752409,
    1.8915178993145003,
    -5.801203960010585,
    0.3111643669578199,
    -0.1521609496625161,
    0.20136540080403034,
    0.04471061572777259,
];

/// Weights of the 5th-order error estimate: e5 = h·Σ_i `E5[i-1]`·k_i = y₁ − ŷ₁⁽⁵⁾, with
/// ŷ₁⁽⁵⁾ = y₀ + h·Σ (B − E5)·k of order 5 (so e5 = O(h⁶)); dop853.f's `er1`, `er6` … `er12`.
pub(in crate::integrators) const E5: [f64; 12] = [
    0.01312004499419488,
    0.0,
    0.0,
    0.0,
    0.0,
    -1.2251564463762044,
    -0.4957589496572502,
    1.6643771824549864,
    -0.35032884874997366,
    0.3341791187130175,
    0.08192320648511571,
    -0.022355307863886294,
];

/// Weights of the 3rd-order error estimate: e3 = h·Σ_i `E3[i-1]`·k_i = y₁ − ŷ₁⁽³⁾, i.e.
/// E3 = B − b̂⁽³⁾, where b̂⁽³⁾ (order 3, so e3 = O(h⁴)) has three nonzero entries, dop853.f's
/// - `bhh1` = 0.244094488188976377952755905512e+00 (stage 1),
/// - `bhh2` = 0.733846688281611857341361741547e+00 (stage 9),
/// - `bhh3` = 0.220588235294117647058823529412e-01 (stage 12).
///
/// dop853.f computes the same thing as Σ b·k − (bhh1·k₁ + bhh2·k₉ + bhh3·k₁₂); here the
/// subtraction was done on the 30-digit values before rounding (SciPy's E3 does it in `f64`
/// and differs by 1 ulp in entries 9 and 12).
pub(in crate::integrators) const E3: [f64; 12] = [
    -0.18980075407240762,
    0.0,
    0.0,
    0.0,
    0.0,
    4.450312892752409,
    1.8915178993145003,
    -5.801203960010585,
    -0.42268232132379197,
    -0.1521609496625161,
    0.20136540080403034,
    0.022651792198360825,
];

/// Nodes of the dense-output stages 14, 15, 16 (c₁₄ = 0.1, c₁₅ = 0.2, c₁₆ = 7/9).
pub(in crate::integrators) const C_EXTRA: [f64; 3] = [0.1, 0.2, 0.7777777777777778];

/// Coupling coefficients of stages 14–16: `A_EXTRA[r][j-1]` = a_{14+r, j}, column j-1 being
/// stage j = 1..16, where stage 13 is k₁₃ = f(t₀ + h, y₁):
///
/// ```text
/// k_{14+r} = f(t₀ + C_EXTRA[r]·h, y₀ + h·Σ_{j<14+r} A_EXTRA[r][j-1]·k_j),   r = 0, 1, 2
/// ```
pub(in crate::integrators) const A_EXTRA: [[f64; 16]; 3] = [
    // stage 14
    [
        0.056167502283047954,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.25350021021662483,
        -0.2462390374708025,
        -0.12419142326381637,
        0.15329179827876568,
        0.00820105229563469,
        0.007567897660545699,
        -0.008298,
        0.0,
        0.0,
        0.0,
    ],
    // stage 15
    [
        0.03183464816350214,
        0.0,
        0.0,
        0.0,
        0.0,
        0.028300909672366776,
        0.053541988307438566,
        -0.05492374857139099,
        0.0,
        0.0,
        -0.00010834732869724932,
        0.0003825710908356584,
        -0.00034046500868740456,
        0.1413124436746325,
        0.0,
        0.0,
    ],
    // stage 16
    [
        -0.42889630158379194,
        0.0,
        0.0,
        0.0,
        0.0,
        -4.697621415361164,
        7.683421196062599,
        4.06898981839711,
        0.3567271874552811,
        0.0,
        0.0,
        0.0,
        -0.0013990241651590145,
        2.9475147891527724,
        -9.15095847217987,
        0.0,
    ],
];

/// Dense-output coefficients d₄ⱼ … d₇ⱼ (dop853.f's `d41` … `d716`), `D[m][j-1]` for stage
/// j = 1..16 (stage 13 = f(t₀ + h, y₁)). After an accepted step, for each component,
///
/// ```text
/// r0 = y₀                      r1 = y₁ − y₀
/// r2 = h·k₁ − r1               r3 = r1 − h·k₁₃ − r2
/// r4 … r7 = h·Σ_{j=1..16} D[0..3][j-1]·k_j
/// u(t₀ + θ·h) = r0 + θ·(r1 + θ₁·(r2 + θ·(r3 + θ₁·(r4 + θ·(r5 + θ₁·(r6 + θ·r7)))))),
/// ```
///
/// with θ = (t − t₀)/h in [0, 1] and θ₁ = 1 − θ (dop853.f's CONTD8, where r0…r7 are CON(1..8)
/// and the polynomial is evaluated as CONPAR = r4 + θ·(r5 + θ₁·(r6 + θ·r7)) first).
/// u(t₀) = y₀, u(t₀ + h) = y₁, u'(t₀) = k₁, u'(t₀ + h) = k₁₃; order 7 for every θ.
pub(in crate::integrators) const D: [[f64; 16]; 4] = [
    // d4j
    [
        -8.428938276109013,
        0.0,
        0.0,
        0.0,
        0.0,
        0.5667149535193777,
        -3.0689499459498917,
        2.38466765651207,
        2.117034582445028,
        -0.871391583777973,
        2.2404374302607883,
        0.6315787787694688,
        -0.08899033645133331,
        18.148505520854727,
        -9.194632392478356,
        -4.436036387594894,
    ],
    // d5j
    [
        10.427508642579134,
        0.0,
        0.0,
        0.0,
        0.0,
        242.28349177525817,
        165.20045171727028,
        -374.5467547226902,
        -22.113666853125306,
        7.733432668472264,
        -30.674084731089398,
        -9.332130526430229,
        15.697238121770845,
        -31.139403219565178,
        -9.35292435884448,
        35.81684148639408,
    ],
    // d6j
    [
        19.985053242002433,
        0.0,
        0.0,
        0.0,
        0.0,
        -387.0373087493518,
        -189.17813819516758,
        527.8081592054236,
        -11.57390253995963,
        6.8812326946963,
        -1.0006050966910838,
        0.7777137798053443,
        -2.778205752353508,
        -60.19669523126412,
        84.32040550667716,
        11.99229113618279,
    ],
    // d7j
    [
        -25.69393346270375,
        0.0,
        0.0,
        0.0,
        0.0,
        -154.18974869023643,
        -231.5293791760455,
        357.6391179106141,
        93.40532418362432,
        -37.45832313645163,
        104.0996495089623,
        29.8402934266605,
        -43.53345659001114,
        96.32455395918828,
        -39.17726167561544,
        -149.72683625798564,
    ],
];
