//! The smoothing kernel: Wendland's C² function in 2-D.

/// Wendland's C² kernel in 2-D with support 2h.
#[derive(Clone, Copy)]
pub(super) struct Wendland {
    h: f64,
    norm: f64,
}

impl Wendland {
    pub(super) fn new(h: f64) -> Wendland {
        Wendland {
            h,
            norm: 7.0 / (4.0 * std::f64::consts::PI * h * h),
        }
    }

    pub(super) fn value(&self, r: f64) -> f64 {
        let q = r / self.h;
        if q >= 2.0 {
            return 0.0;
        }
        self.norm * (1.0 - 0.5 * q).powi(4) * (1.0 + 2.0 * q)
    }

    /// dW/dr = norm·(−5q(1 − q/2)³)/h.
    pub(super) fn derivative(&self, r: f64) -> f64 {
        let q = r / self.h;
        if q >= 2.0 {
            return 0.0;
        }
        -self.norm * 5.0 * q * (1.0 - 0.5 * q).powi(3) / self.h
    }
}
