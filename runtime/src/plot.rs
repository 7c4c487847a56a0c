//! Energy charts as PNG or SVG, drawn with plotters and a bundled font (no system fonts needed).

use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

use crate::output::{with_temporary, write_atomic};
use crate::{Error, Result, State, Trajectory};

/// DejaVu Sans, under the Bitstream Vera licence (see `assets/DejaVuSans-LICENSE.txt`).
const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

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
pub fn energy<S: State>(path: impl AsRef<Path>, runs: &[(&str, &Trajectory<S>)]) -> Result<()> {
    energy_with(path, runs, &EnergyPlot::default())
}

/// [`energy`] with a chosen look.
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
        series.push(Series {
            label: (*label).to_owned(),
            points,
        });
    }
    let y_label = if look.relative {
        "E(t) / E(0)"
    } else {
        "energy"
    };
    let chart = Chart {
        title: &look.title,
        x_label: "t",
        y_label,
        log_y: look.log_y,
        series,
    };
    chart.write(path, look.size)
}

/// One labelled line.
pub(crate) struct Series {
    pub(crate) label: String,
    pub(crate) points: Vec<(f64, f64)>,
}

/// A line chart of several series, the shared drawing code of every odyn chart.
pub(crate) struct Chart<'a> {
    pub(crate) title: &'a str,
    pub(crate) x_label: &'a str,
    pub(crate) y_label: &'a str,
    pub(crate) log_y: bool,
    pub(crate) series: Vec<Series>,
}

impl Chart<'_> {
    pub(crate) fn write(&self, path: &Path, size: (u32, u32)) -> Result<()> {
        register_bundled_font(path)?;
        let finite =
            |&(x, y): &(f64, f64)| x.is_finite() && y.is_finite() && (!self.log_y || y > 0.0);
        let points = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().copied().filter(finite));
        let (x, y) = bounds(points).ok_or_else(|| {
            Error::invalid(
                "plot",
                "no finite points to draw (on a log axis, no positive ones)",
            )
        })?;
        match path.extension().and_then(|e| e.to_str()) {
            Some("svg") => {
                let mut text = String::new();
                {
                    let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
                    self.draw(&root, x, y)
                        .map_err(|reason| plot_error(path, reason))?;
                }
                write_atomic(path, text.as_bytes())
            }
            Some("png") => with_temporary(path, ".png", |temp| {
                let root = BitMapBackend::new(temp, size).into_drawing_area();
                self.draw(&root, x, y)
                    .map_err(|reason| plot_error(path, reason))
            }),
            _ => Err(Error::invalid(
                "plot path",
                format!("`{}` must end in .png or .svg", path.display()),
            )),
        }
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        (x0, x1): (f64, f64),
        (y0, y1): (f64, f64),
    ) -> std::result::Result<(), String> {
        let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        root.fill(&WHITE).map_err(e)?;
        let mut builder = ChartBuilder::on(root);
        builder
            .caption(self.title, ("sans-serif", 24))
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(80);
        if self.log_y {
            let (lo, hi) = (y0 / 1.5, y1 * 1.5);
            let mut chart = builder
                .build_cartesian_2d(x0..x1, (lo..hi).log_scale())
                .map_err(e)?;
            chart
                .configure_mesh()
                .x_desc(self.x_label)
                .y_desc(self.y_label)
                .y_label_formatter(&|v| format!("{v:.0e}"))
                .label_style(("sans-serif", 16))
                .draw()
                .map_err(e)?;
            self.draw_series(&mut chart).map_err(e)?;
        } else {
            let pad = 0.05 * (y1 - y0).max(1e-12 * y1.abs().max(1.0));
            let mut chart = builder
                .build_cartesian_2d(x0..x1, (y0 - pad)..(y1 + pad))
                .map_err(e)?;
            chart
                .configure_mesh()
                .x_desc(self.x_label)
                .y_desc(self.y_label)
                .label_style(("sans-serif", 16))
                .draw()
                .map_err(e)?;
            self.draw_series(&mut chart).map_err(e)?;
        }
        root.present().map_err(e)
    }

    fn draw_series<'c, DB, Y>(
        &self,
        chart: &mut ChartContext<'c, DB, Cartesian2d<plotters::coord::types::RangedCoordf64, Y>>,
    ) -> std::result::Result<(), DrawingAreaErrorKind<DB::ErrorType>>
    where
        DB: DrawingBackend + 'c,
        Y: Ranged<ValueType = f64>,
    {
        for (i, s) in self.series.iter().enumerate() {
            let (r, g, b) = PALETTE[i % PALETTE.len()];
            let color = RGBColor(r, g, b).to_rgba();
            let style = ShapeStyle::from(color).stroke_width(2);
            let points = s
                .points
                .iter()
                .copied()
                .filter(|(x, y)| x.is_finite() && y.is_finite());
            chart
                .draw_series(LineSeries::new(points, style))?
                .label(s.label.as_str())
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 24, y)], style));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 16))
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
    }
}

/// Matplotlib's `tab10`: distinct on white, and legible to most colour-blind readers.
const PALETTE: [(u8, u8, u8); 10] = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
    (188, 189, 34),
    (23, 190, 207),
];

fn bounds(points: impl Iterator<Item = (f64, f64)>) -> Option<((f64, f64), (f64, f64))> {
    let mut b: Option<((f64, f64), (f64, f64))> = None;
    for (x, y) in points {
        b = Some(match b {
            None => ((x, x), (y, y)),
            Some(((x0, x1), (y0, y1))) => ((x0.min(x), x1.max(x)), (y0.min(y), y1.max(y))),
        });
    }
    b.map(|((x0, x1), y)| {
        if x1 > x0 {
            ((x0, x1), y)
        } else {
            ((x0, x0 + 1.0), y)
        }
    })
}

fn plot_error(path: &Path, reason: String) -> Error {
    Error::Plot {
        path: path.to_path_buf(),
        reason,
    }
}

fn register_bundled_font(path: &Path) -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok =
        *REGISTERED.get_or_init(|| register_font("sans-serif", FontStyle::Normal, FONT).is_ok());
    if ok {
        Ok(())
    } else {
        Err(plot_error(
            path,
            "the bundled font failed to load".to_owned(),
        ))
    }
}
