//! A study's results read back: per method, its observed order and tolerance proportionality;
//! as a CSV table and as a chart.

use std::path::Path;

use super::*;
use crate::output::{number, write_table};
use crate::{Method, Result, Stepping};

impl WorkPrecisionSet {
    /// The measurements of one method, in the order of the study.
    pub fn of(&self, method: Method) -> impl Iterator<Item = &Measurement> {
        self.measurements.iter().filter(move |m| m.method == method)
    }

    /// For a fixed-step method, the least-squares slope of log(error) against log(dt) over its
    /// finite, non-zero errors: its observed order. `None` with fewer than two distinct such
    /// steps, and for adaptive methods (whose error follows the tolerance, not a step).
    pub fn observed_order(&self, method: Method) -> Option<f64> {
        let points: Vec<(f64, f64)> = self
            .of(method)
            .filter(|m| m.error.is_finite() && m.error > 0.0)
            .filter_map(|m| Some((m.stepping.dt()?.ln(), m.error.ln())))
            .collect();
        slope(&points)
    }

    /// For an adaptive method, the least-squares slope of log(error) against log(rtol) over its
    /// finite, non-zero errors: 1 when the error follows the tolerance proportionally. `None`
    /// with fewer than two such runs, and for fixed-step methods.
    pub fn tolerance_proportionality(&self, method: Method) -> Option<f64> {
        let points: Vec<(f64, f64)> = self
            .of(method)
            .filter(|m| m.error.is_finite() && m.error > 0.0)
            .filter_map(|m| Some((m.stepping.rtol()?.ln(), m.error.ln())))
            .collect();
        slope(&points)
    }

    /// Writes `scene,method,dt,rtol,atol,steps,rejected,error,energy_error,seconds,evaluations`,
    /// atomically. Evaluations count force, Jacobian and ∂f/∂t evaluations together; a failed
    /// run has an infinite error and no time.
    pub fn write_csv(&self, path: impl AsRef<Path>) -> Result<()> {
        let rows: Vec<Vec<String>> = self
            .measurements
            .iter()
            .map(|m| {
                let (dt, rtol, atol) = match &m.stepping {
                    Stepping::Fixed(dt) => (number(*dt), String::new(), String::new()),
                    Stepping::Adaptive(t) => (
                        String::new(),
                        number(t.rtol),
                        match &t.atol {
                            crate::Atol::Scalar(a) => number(*a),
                            crate::Atol::PerComponent(_) => "per-component".to_owned(),
                        },
                    ),
                };
                vec![
                    self.scene.clone(),
                    m.method.name().to_owned(),
                    dt,
                    rtol,
                    atol,
                    m.stats.steps.to_string(),
                    m.stats.rejected.to_string(),
                    number(m.error),
                    m.energy_error.map_or_else(String::new, number),
                    number(m.seconds),
                    m.evaluations().to_string(),
                ]
            })
            .collect();
        let header = [
            "scene",
            "method",
            "dt",
            "rtol",
            "atol",
            "steps",
            "rejected",
            "error",
            "energy_error",
            "seconds",
            "evaluations",
        ];
        write_table(path, &header, &rows)
    }

    /// Draws `accuracy` against `cost`, log-log, one line per method with a marker per run, as
    /// PNG or SVG, titled with the study's title and a note that lower left is better. In an
    /// SVG each marker shows its run's dt or rtol, error and cost on hover. Failed runs, and
    /// runs without the chosen error, are left out.
    #[cfg(feature = "plot")]
    pub fn plot(&self, path: impl AsRef<Path>, accuracy: Accuracy, cost: Cost) -> Result<()> {
        use crate::plot::{Chart, Series};
        let mut methods: Vec<Method> = Vec::new();
        for m in &self.measurements {
            if !methods.contains(&m.method) {
                methods.push(m.method);
            }
        }
        let series = methods
            .into_iter()
            .map(|method| {
                let (points, notes): (Vec<_>, Vec<_>) = self
                    .of(method)
                    .filter(|m| !m.diverged)
                    .filter_map(|m| {
                        let error = match accuracy {
                            Accuracy::FinalState => m.error,
                            Accuracy::Energy => m.energy_error?,
                        };
                        let (work, spent) = match cost {
                            Cost::Seconds => (m.seconds, format!("{:.3e} s", m.seconds)),
                            Cost::Evaluations => {
                                let n = m.evaluations();
                                (n as f64, format!("{n} evaluations"))
                            }
                        };
                        let stepping = match &m.stepping {
                            Stepping::Fixed(dt) => format!("dt = {dt:e}"),
                            Stepping::Adaptive(t) => match &t.atol {
                                crate::Atol::Scalar(atol) => {
                                    format!("rtol = {:e}, atol = {atol:e}", t.rtol)
                                }
                                crate::Atol::PerComponent(_) => format!("rtol = {:e}", t.rtol),
                            },
                        };
                        let note = format!("{stepping}: error {error:.2e}, {spent}");
                        Some(((error, work), note))
                    })
                    .unzip();
                let kind = if method.is_adaptive() {
                    " (rtol)"
                } else {
                    " (dt)"
                };
                Series::line_and_markers(format!("{}{kind}", method.label()), points)
                    .with_notes(notes)
            })
            .collect();
        let (what, unit) = match cost {
            Cost::Seconds => ("time", "wall time (s)"),
            Cost::Evaluations => ("evaluations", "f + J evaluations"),
        };
        let error = match accuracy {
            Accuracy::FinalState => "final-state error",
            Accuracy::Energy => "max relative energy error",
        };
        Chart {
            title: format!("{}: {error} against {what}", self.title),
            note: "lower left is better: more accurate for less work".to_owned(),
            x_label: error.to_owned(),
            y_label: unit.to_owned(),
            log_x: true,
            log_y: true,
            series,
        }
        .write(path, (1000, 640))
    }
}

/// Least-squares slope of y against x; `None` with fewer than two distinct x.
fn slope(points: &[(f64, f64)]) -> Option<f64> {
    if points.len() < 2 {
        return None;
    }
    let n = points.len() as f64;
    let (mx, my) = (
        points.iter().map(|p| p.0).sum::<f64>() / n,
        points.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let cov: f64 = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let var: f64 = points.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    (var > 0.0).then(|| cov / var)
}
