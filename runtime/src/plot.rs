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
        series.push(Series::line(*label, points));
    }
    let chart = Chart {
        title: look.title.clone(),
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
        legend: Legend::UpperLeft,
    };
    chart.write(path, look.size)
}

/// One labelled series of a [`Chart`].
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// (x, y) points; non-finite ones (and non-positive ones on a log axis) are skipped.
    pub points: Vec<(f64, f64)>,
    /// Draw markers at the points instead of a line through them.
    pub markers: bool,
}

impl Series {
    /// A line through `points`.
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            markers: false,
        }
    }

    /// Markers at `points`.
    pub fn markers(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            markers: true,
        }
    }
}

/// A chart of several series, linear or logarithmic on each axis, written as PNG or SVG.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Chart {
    /// Title above the plot.
    pub title: String,
    /// Label of the horizontal axis.
    pub x_label: String,
    /// Label of the vertical axis.
    pub y_label: String,
    /// Logarithmic horizontal axis.
    pub log_x: bool,
    /// Logarithmic vertical axis.
    pub log_y: bool,
    /// The series, drawn in order with the `tab10` colours.
    pub series: Vec<Series>,
    /// Where the legend goes (default upper left).
    pub legend: Legend,
}

/// A corner for the legend of a [`Chart`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Legend {
    /// Upper left.
    #[default]
    UpperLeft,
    /// Upper right.
    UpperRight,
    /// Lower left.
    LowerLeft,
    /// Lower right.
    LowerRight,
}

impl Chart {
    /// Draws the chart at `size` pixels and writes it atomically to `path` (`.png` or `.svg`).
    pub fn write(&self, path: impl AsRef<Path>, size: (u32, u32)) -> Result<()> {
        let path = path.as_ref();
        register_bundled_font(path)?;
        let (x, y) = bounds(
            self.series
                .iter()
                .flat_map(|s| s.points.iter().copied().filter(|&p| self.drawable(p))),
        )
        .ok_or_else(|| {
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

    fn drawable(&self, (x, y): (f64, f64)) -> bool {
        x.is_finite() && y.is_finite() && (!self.log_x || x > 0.0) && (!self.log_y || y > 0.0)
    }

    /// A point as drawn: logarithmic axes are drawn linearly in log₁₀ of the data (plotters' own
    /// log axis cannot span the hundreds of decades a diverging run covers).
    fn project(&self, (x, y): (f64, f64)) -> (f64, f64) {
        (
            if self.log_x { x.log10() } else { x },
            if self.log_y { y.log10() } else { y },
        )
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        (x0, x1): (f64, f64),
        (y0, y1): (f64, f64),
    ) -> std::result::Result<(), String> {
        let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        root.fill(&WHITE).map_err(e)?;
        let (x0, y0) = self.project((x0, y0));
        let (x1, y1) = self.project((x1, y1));
        let (x0, x1) = pad(x0, x1);
        let (y0, y1) = pad(y0, y1);
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 24))
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(90)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(e)?;
        let (log_x, log_y) = (self.log_x, self.log_y);
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&|v| axis_label(*v, log_x))
            .y_label_formatter(&|v| axis_label(*v, log_y))
            .label_style(("sans-serif", 16))
            .draw()
            .map_err(e)?;
        for (i, s) in self.series.iter().enumerate() {
            // A series with nothing to draw (every run diverged) stays out of the legend too;
            // its colour stays reserved so the others keep theirs.
            if !s.points.iter().any(|&p| self.drawable(p)) {
                continue;
            }
            let (r, g, b) = PALETTE[i % PALETTE.len()];
            let color = RGBColor(r, g, b).to_rgba();
            let style = ShapeStyle::from(color).stroke_width(2);
            let points = s
                .points
                .iter()
                .copied()
                .filter(|&p| self.drawable(p))
                .map(|p| self.project(p));
            let drawn = if s.markers {
                chart
                    .draw_series(points.map(|p| Circle::new(p, 5, style.filled())))
                    .map_err(e)?
            } else {
                chart
                    .draw_series(LineSeries::new(points, style))
                    .map_err(e)?
            };
            drawn
                .label(s.label.as_str())
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 24, y)], style));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 16))
            .position(match self.legend {
                Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
                Legend::UpperRight => SeriesLabelPosition::UpperRight,
                Legend::LowerLeft => SeriesLabelPosition::LowerLeft,
                Legend::LowerRight => SeriesLabelPosition::LowerRight,
            })
            .draw()
            .map_err(e)?;
        root.present().map_err(e)
    }
}

/// Widens a range a little (and a degenerate one to a unit) so lines do not sit on the frame.
fn pad(lo: f64, hi: f64) -> (f64, f64) {
    let span = if hi > lo { hi - lo } else { 1.0 };
    (lo - 0.05 * span, hi + 0.05 * span)
}

/// A tick label: on a log axis `v` is log₁₀ of the value.
fn axis_label(v: f64, log: bool) -> String {
    if log {
        if (v - v.round()).abs() < 1e-9 {
            format!("1e{}", v.round())
        } else {
            format!("{:.1e}", 10f64.powf(v))
        }
    } else if v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-3) {
        format!("{v:.0e}")
    } else {
        // Six significant digits, so 0.6000000000000001 reads 0.6.
        let scale = 10f64.powi(5 - v.abs().max(1e-300).log10().floor() as i32);
        format!("{}", (v * scale).round() / scale)
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

/// One projection of a scene: line segments (a particle model's links) and highlighted points
/// (its pinned particles) in a plane, drawn to scale.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct View {
    /// Panel title (`front (x–y)`).
    pub title: String,
    /// Horizontal axis label.
    pub x_label: String,
    /// Vertical axis label.
    pub y_label: String,
    /// Segments to draw, end to end.
    pub segments: Vec<[(f64, f64); 2]>,
    /// Points drawn as red dots over the segments.
    pub points: Vec<(f64, f64)>,
    /// The region shown, ((x₀, x₁), (y₀, y₁)); keep it fixed across frames so motion shows.
    pub bounds: ((f64, f64), (f64, f64)),
}

/// Draws `views` side by side under `title`, each panel to scale (equal units on both axes),
/// and writes the image atomically to `path` (`.png` or `.svg`).
pub fn views(path: impl AsRef<Path>, title: &str, views: &[View], size: (u32, u32)) -> Result<()> {
    let path = path.as_ref();
    register_bundled_font(path)?;
    if views.is_empty() {
        return Err(Error::invalid("views", "nothing to draw"));
    }
    match path.extension().and_then(|e| e.to_str()) {
        Some("svg") => {
            let mut text = String::new();
            {
                let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
                draw_views(&root, title, views).map_err(|reason| plot_error(path, reason))?;
            }
            write_atomic(path, text.as_bytes())
        }
        Some("png") => with_temporary(path, ".png", |temp| {
            let root = BitMapBackend::new(temp, size).into_drawing_area();
            draw_views(&root, title, views).map_err(|reason| plot_error(path, reason))
        }),
        _ => Err(Error::invalid(
            "plot path",
            format!("`{}` must end in .png or .svg", path.display()),
        )),
    }
}

fn draw_views<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    views: &[View],
) -> std::result::Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let root = root.titled(title, ("sans-serif", 24)).map_err(e)?;
    let panels = root.split_evenly((1, views.len()));
    let (r, g, b) = PALETTE[0];
    let line = ShapeStyle::from(RGBColor(r, g, b).to_rgba()).stroke_width(1);
    for (panel, view) in panels.iter().zip(views) {
        let ((x0, x1), (y0, y1)) = view.bounds;
        // Equal scale: widen the shorter side of the region to the panel's aspect ratio.
        let (w, h) = panel.dim_in_pixel();
        let (w, h) = (
            f64::from(w.saturating_sub(80).max(1)),
            f64::from(h.saturating_sub(90).max(1)),
        );
        let (span_x, span_y) = ((x1 - x0).max(1e-12), (y1 - y0).max(1e-12));
        let scale = (span_x / w).max(span_y / h);
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        let (hx, hy) = (0.5 * scale * w, 0.5 * scale * h);
        let mut chart = ChartBuilder::on(panel)
            .caption(&view.title, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d(cx - hx..cx + hx, cy - hy..cy + hy)
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc(&view.x_label)
            .y_desc(&view.y_label)
            .label_style(("sans-serif", 14))
            .draw()
            .map_err(e)?;
        chart
            .draw_series(
                view.segments
                    .iter()
                    .map(|&[a, b]| PathElement::new([a, b], line)),
            )
            .map_err(e)?;
        chart
            .draw_series(view.points.iter().map(|&p| Circle::new(p, 4, RED.filled())))
            .map_err(e)?;
    }
    root.present().map_err(e)
}
