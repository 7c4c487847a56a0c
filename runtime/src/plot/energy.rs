//! Energy charts: the energy of several runs against time, absolute or relative to E(0).

use std::path::Path;

use super::{Chart, Series};
use crate::{Error, Result, State, Trajectory};

/// How an energy chart looks.
#[derive(Clone, Debug, PartialEq)]
pub struct EnergyPlot {
    /// Chart title (default: none).
    pub title: String,
    /// Plot E(t)/E(0) instead of E(t) (default false).
    pub relative: bool,
    /// Logarithmic energy axis (default false); every plotted energy must then be positive.
    pub log_y: bool,
    /// Image size in pixels (default 960 × 600).
    pub size: (u32, u32),
}

impl Default for EnergyPlot {
    fn default() -> Self {
        EnergyPlot {
            title: String::new(),
            relative: false,
            log_y: false,
            size: (960, 600),
        }
    }
}

/// Draws the energy of several runs on one chart, written atomically to `path` (`.png` or
/// `.svg`), with the default [`EnergyPlot`] look.
///
/// Errors: [`Error::InvalidInput`] when a run's model defines no `fn energy`, and as
/// [`Chart::write`] (a path that is not `.png`/`.svg`, energies that cannot be drawn, a file
/// that cannot be written).
pub fn energy<S: State>(path: impl AsRef<Path>, runs: &[(&str, &Trajectory<S>)]) -> Result<()> {
    energy_with(path, runs, &EnergyPlot::default())
}

/// [`energy`] with a chosen look.
///
/// Errors: as [`energy`].
pub fn energy_with<S: State>(
    path: impl AsRef<Path>,
    runs: &[(&str, &Trajectory<S>)],
    look: &EnergyPlot,
) -> Result<()> {
    let path = path.as_ref();
    let mut series = Vec::with_capacity(runs.len());
    for (label, run) in runs {
        let e0 = run.first().energy.ok_or_else(|| {
            Error::invalid(
                "plot",
                format!("`{}` defines no `fn energy` to plot", run.model),
            )
        })?;
        let scale = if look.relative { e0 } else { 1.0 };
        let points: Vec<(f64, f64)> = run.energies().map(|(t, e)| (t, e / scale)).collect();
        series.push(Series::line(*label, points));
    }
    let chart = Chart {
        title: look.title.clone(),
        note: String::new(),
        x_label: "t".to_owned(),
        y_label: if look.relative {
            "E(t) / E(0)"
        } else {
            "energy"
        }
        .to_owned(),
        log_x: false,
        log_y: look.log_y,
        series,
    };
    chart.write(path, look.size)
}
