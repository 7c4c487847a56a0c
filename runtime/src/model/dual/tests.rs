//! The rules at the arguments where the textbook forms fail (the fourth hardening probe): each
//! expected derivative is the closed form of f′.

use super::Dual;

fn x(value: f64) -> Dual {
    Dual::new(value, 1.0)
}

#[test]
fn rounding_functions_have_derivative_zero_and_fract_one() {
    for a in [-2.5, -0.0, 0.0, 0.3, 7.5, 1e300] {
        for f in [Dual::floor, Dual::ceil, Dual::round, Dual::trunc] {
            assert_eq!(f(x(a)).derivative(), 0.0);
        }
        assert_eq!(x(a).fract().derivative(), 1.0);
        assert_eq!(x(a).fract().value(), a.fract());
    }
}

#[test]
fn constant_exponents_are_finite_at_negative_and_zero_bases() {
    let c = Dual::constant;
    // d/dx x³ = 3x², d/dx x² = 2x, d/dx x^1.5 = 1.5·√x.
    assert_eq!(x(-2.0).powf(c(3.0)).derivative(), 12.0);
    assert_eq!(x(-2.0).powf(c(2.0)).derivative(), -4.0);
    assert_eq!(x(0.0).powf(c(3.0)).derivative(), 0.0);
    assert_eq!(x(0.0).powf(c(1.5)).derivative(), 0.0);
    assert_eq!(x(4.0).powf(c(1.5)).derivative(), 3.0);
}

#[test]
fn hypot_and_atan2_do_not_overflow_or_underflow() {
    let c = Dual::constant;
    let half = std::f64::consts::FRAC_1_SQRT_2;
    for s in [1e200, 1e-200, 1.0] {
        let h = x(s).hypot(c(s));
        assert!((h.derivative() - half).abs() < 1e-15, "{s}: {h}");
        // ∂atan2(a, b)/∂a = b/(a² + b²) = 1/(2s) at a = b = s.
        let a = x(s).atan2(c(s));
        assert!((a.derivative() * 2.0 * s - 1.0).abs() < 1e-15, "{s}: {a}");
    }
}

#[test]
fn max_and_min_drop_a_nan_as_f64_does() {
    let nan = (x(1.0) * x(1.0) - 4.0).sqrt();
    assert!(nan.value().is_nan());
    let m = nan.max(Dual::constant(0.0));
    assert_eq!((m.value(), m.derivative()), (0.0, 0.0));
    let m = Dual::constant(0.0).min(nan);
    assert_eq!((m.value(), m.derivative()), (0.0, 0.0));
    // A tie takes the first argument's derivative, as the generated Jacobian does.
    assert_eq!(x(1.0).max(Dual::constant(1.0)).derivative(), 1.0);
}

#[test]
fn the_logistic_quotient_is_finite_where_its_square_overflows() {
    // σ(x) = eˣ/(1 + eˣ), σ′ = σ(1 − σ) ≈ e⁻⁷⁰⁹ at x = 709, far below rounding of σ = 1.
    let e = x(709.0).exp();
    let s = e / (e + 1.0);
    assert!(
        s.derivative().is_finite() && s.derivative().abs() < 1e-300,
        "{s}"
    );
}

#[test]
fn comparisons_read_the_values_only() {
    assert!(Dual::new(1.0, 5.0) <= Dual::new(1.0, -5.0));
    assert_eq!(Dual::new(1.0, 5.0), Dual::new(1.0, -5.0));
    assert!(Dual::new(f64::NAN, 0.0).is_nan());
    assert_eq!(
        x(90.0).to_radians().derivative(),
        std::f64::consts::PI / 180.0
    );
    assert_eq!(x(-7.0).rem_euclid(Dual::constant(3.0)).value(), 2.0);
}
