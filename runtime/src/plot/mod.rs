//! Charts as PNG or SVG, drawn with plotters and a bundled font (no system fonts needed): energy
//! against time, general line/marker charts, and to-scale views of particle scenes.

mod axes;
mod draw;
mod field;

pub use field::{Field, FieldStyle, field_animation, field_image};

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::{Error, Result, State, Trajectory};
use axes::Axis;
use draw::{LegendEntry, PixelRect};

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

/// How a [`Series`] is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Style {
    /// A line through the points, with a few markers of the series' own shape along it so lines
    /// that coincide stay distinguishable.
    #[default]
    Line,
    /// A line with a marker at every point: for short series such as work-precision sweeps.
    LineAndMarkers,
    /// Markers only.
    Markers,
}

/// One labelled series of a [`Chart`].
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend text; an empty label keeps the series out of the legend.
    pub label: String,
    /// (x, y) points; non-finite ones (and non-positive ones on a log axis) are skipped.
    pub points: Vec<(f64, f64)>,
    /// How the points are drawn.
    pub style: Style,
    /// One note per point (such as the rtol or dt of the run it came from), shown when the
    /// pointer rests on the point in an SVG chart; empty for none.
    pub notes: Vec<String>,
}

impl Series {
    /// A line through `points`.
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            style: Style::Line,
            notes: Vec::new(),
        }
    }

    /// A line with a marker at every point.
    pub fn line_and_markers(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            style: Style::LineAndMarkers,
            notes: Vec::new(),
        }
    }

    /// With a note for each point, shown on hover in an SVG chart (see [`Series::notes`]).
    pub fn with_notes(self, notes: Vec<String>) -> Self {
        Series { notes, ..self }
    }

    /// Markers at `points`.
    pub fn markers(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            style: Style::Markers,
            notes: Vec::new(),
        }
    }
}

/// A chart of several series, linear or logarithmic on each axis, written as PNG or SVG.
///
/// The legend sits in a panel to the right of the plot, so it never covers data. A line with
/// more points than the plot has pixel columns is drawn through each column's extremes (see
/// `draw::decimate`): a million recorded steps draw as fast as a few thousand and stay inside
/// the frame, each segment drawn on its own so wide strokes have no joins to spike.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Chart {
    /// Title above the plot.
    pub title: String,
    /// A smaller line under the title: how to read the chart (empty for none).
    pub note: String,
    /// Label of the horizontal axis.
    pub x_label: String,
    /// Label of the vertical axis.
    pub y_label: String,
    /// Logarithmic horizontal axis.
    pub log_x: bool,
    /// Logarithmic vertical axis.
    pub log_y: bool,
    /// The series, drawn in order with the `tab10` colours (then further hues, so no two of a
    /// chart share a colour) and one of six marker shapes each.
    pub series: Vec<Series>,
}

impl Chart {
    /// Draws the chart at `size` pixels and writes it atomically to `path` (`.png` or `.svg`).
    /// In an SVG, each point that has a note (see [`Series::notes`]) shows its series' label and
    /// the note when the pointer rests on it.
    ///
    /// Errors: [`Error::InvalidInput`] for a path that is not `.png`/`.svg`, a size outside
    /// 16–16384 pixels, or data that cannot be drawn (no finite point; on a linear axis, values
    /// beyond ±1e300); [`Error::Io`] when the file cannot be written.
    pub fn write(&self, path: impl AsRef<Path>, size: (u32, u32)) -> Result<()> {
        let path = path.as_ref();
        draw::image_kind(path)?;
        let (x, y) = self.axes()?;
        draw::write_image(
            path,
            size,
            |root| self.draw(root, x, y).map(|_| ()),
            |root| self.draw(root, x, y).map(|drawn| hover_notes(&drawn.notes)),
        )
    }

    /// The axes that show every drawable point.
    fn axes(&self) -> Result<(Axis, Axis)> {
        let points = || self.series.iter().flat_map(|s| s.points.iter().copied());
        let probe = |log| Axis {
            log,
            lo: 0.0,
            hi: 0.0,
        };
        let (px, py) = (probe(self.log_x), probe(self.log_y));
        let drawable = |&(x, y): &(f64, f64)| px.takes(x) && py.takes(y);
        let x = Axis::fit("plot x", self.log_x, points().filter(drawable).map(|p| p.0));
        let y = Axis::fit("plot y", self.log_y, points().filter(drawable).map(|p| p.1));
        match (x, y) {
            (Ok(x), Ok(y)) => Ok((x, y)),
            (Err(_), _) | (_, Err(_)) if points().find(drawable).is_none() => Err(Error::invalid(
                "plot",
                "no finite points to draw (on a log axis, no positive ones)",
            )),
            (Err(e), _) | (_, Err(e)) => Err(e),
        }
    }

    /// Draws onto `root`; returns the plotting area's pixel rectangle and where the noted
    /// points were drawn.
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        x: Axis,
        y: Axis,
    ) -> std::result::Result<Drawn, String> {
        let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        root.fill(&WHITE).map_err(e)?;
        let drawable = |&(px, py): &(f64, f64)| x.takes(px) && y.takes(py);
        // A series with nothing to draw (every run diverged) stays out of the legend too; its
        // colour and shape stay reserved so the others keep theirs.
        let shown: Vec<usize> = (0..self.series.len())
            .filter(|&i| self.series[i].points.iter().any(drawable))
            .collect();
        let labelled = shown.iter().filter(|&&i| !self.series[i].label.is_empty());
        let width = root.dim_in_pixel().0;
        let legend = draw::legend_width(labelled.map(|&i| self.series[i].label.as_str()), width);
        let (plot, panel) = root.split_horizontally(width - legend);
        let heading = match (self.title.is_empty(), self.note.is_empty()) {
            (true, true) => 0,
            (false, true) => 34,
            (_, false) => 54,
        };
        let (head, plot) = plot.split_vertically(heading);
        let centre = |text: &str, y, size| -> std::result::Result<(), String> {
            let font = ("sans-serif", size).into_font();
            let (w, _) = head
                .estimate_text_size(text, &font.clone().into())
                .map_err(e)?;
            let x = (head.dim_in_pixel().0 as i32 - w as i32) / 2;
            head.draw(&Text::new(text.to_owned(), (x.max(4), y), font))
                .map_err(e)
        };
        if !self.title.is_empty() {
            centre(&self.title, 10, 22.0)?;
        }
        if !self.note.is_empty() {
            centre(
                &self.note,
                if self.title.is_empty() { 10 } else { 36 },
                15.0,
            )?;
        }
        let mut chart = ChartBuilder::on(&plot)
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(90)
            .build_cartesian_2d(x.lo..x.hi, y.lo..y.hi)
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
        let columns = chart.plotting_area().dim_in_pixel().0;
        let mut entries = Vec::new();
        let mut notes = Vec::new();
        for &i in &shown {
            let s = &self.series[i];
            let style = ShapeStyle::from(draw::colour(i)).stroke_width(2);
            let points: Vec<(f64, f64)> = s
                .points
                .iter()
                .filter(|p| drawable(p))
                .map(|&(px, py)| (x.project(px), y.project(py)))
                .collect();
            let line = s.style != Style::Markers;
            if line {
                let drawn = draw::decimate(&points, (x.lo, x.hi), columns);
                chart
                    .draw_series(
                        drawn
                            .windows(2)
                            .map(|w| PathElement::new(vec![w[0], w[1]], style)),
                    )
                    .map_err(e)?;
            }
            let at: Vec<usize> = match s.style {
                Style::Line => draw::marker_indices(points.len(), 8, i, self.series.len()),
                Style::LineAndMarkers | Style::Markers => (0..points.len()).collect(),
            };
            let (ox, oy) = plot.get_base_pixel();
            for k in at {
                let (px, py) = chart.backend_coord(&points[k]);
                draw::draw_marker(&plot, i, (px - ox, py - oy), style)?;
            }
            // The notes go with the drawable points, in their order.
            let noted = s.points.iter().filter(|p| drawable(p)).zip(&s.notes);
            for ((px, py), note) in noted {
                let at = chart.backend_coord(&(x.project(*px), y.project(*py)));
                let text = if s.label.is_empty() {
                    note.clone()
                } else {
                    format!("{}: {note}", s.label)
                };
                notes.push((at, text));
            }
            if !s.label.is_empty() {
                entries.push(LegendEntry {
                    label: &s.label,
                    colour: draw::colour(i),
                    line,
                    shape: Some(i),
                });
            }
        }
        draw::draw_legend(&panel, &entries, 56)?;
        Ok(Drawn {
            plot: chart.plotting_area().get_pixel_range(),
            notes,
        })
    }
}

/// What [`Chart::draw`] drew where.
struct Drawn {
    /// The plotting area's pixel rectangle.
    #[cfg_attr(not(test), expect(dead_code, reason = "read by the chart-bounds test"))]
    plot: PixelRect,
    /// The noted points: pixel and text.
    notes: Vec<((i32, i32), String)>,
}

/// SVG markup that shows each note as the tooltip of an invisible disc over its point.
fn hover_notes(notes: &[((i32, i32), String)]) -> String {
    let escape = |text: &str| {
        text.replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;")
    };
    notes
        .iter()
        .map(|((x, y), note)| {
            format!(
                "<circle cx=\"{x}\" cy=\"{y}\" r=\"7\" fill=\"none\" pointer-events=\"all\">\
                 <title>{}</title></circle>\n",
                escape(note)
            )
        })
        .collect()
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
        // Six significant digits with trailing zeros dropped, so 1.2e5 and 1.4e5 stay apart.
        let text = format!("{v:.5e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        format!("{mantissa}e{exponent}")
    } else {
        // Six significant digits, so 0.6000000000000001 reads 0.6.
        let scale = 10f64.powi(5 - v.abs().max(1e-300).log10().floor() as i32);
        format!("{}", (v * scale).round() / scale)
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
    /// More segments, drawn over `segments` in the second colour (a second trajectory).
    pub highlighted: Vec<[(f64, f64); 2]>,
    /// Stroke width of the segments in pixels (0, the default, draws 1: right for dense
    /// trajectories; rods and links read better at 3).
    pub line_width: u32,
    /// Points drawn as red dots over the segments.
    pub points: Vec<(f64, f64)>,
    /// The region shown, ((x₀, x₁), (y₀, y₁)); keep it fixed across frames so motion shows.
    pub bounds: ((f64, f64), (f64, f64)),
}

/// Draws `views` side by side under `title`, each panel to scale (equal units on both axes),
/// and writes the image atomically to `path` (`.png` or `.svg`).
///
/// Errors: [`Error::InvalidInput`] for no views, a view whose bounds are not a finite range, a
/// segment or point that is not finite, or a path or size [`Chart::write`] would refuse.
pub fn views(path: impl AsRef<Path>, title: &str, views: &[View], size: (u32, u32)) -> Result<()> {
    let path = path.as_ref();
    draw::image_kind(path)?;
    let regions = regions(views)?;
    draw::write_image(
        path,
        size,
        |root| draw_views(root, title, views, &regions),
        |root| draw_views(root, title, views, &regions).map(|()| String::new()),
    )
}

/// One frame of an [`animation`]: a title over views drawn as [`views`] draws them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    /// Title above the panels (`t = 1.25 s`).
    pub title: String,
    /// The panels, side by side.
    pub views: Vec<View>,
}

/// Draws each frame as [`views`] would and writes them atomically to `path` as an animated GIF
/// that loops forever, `delay_ms` milliseconds a frame (pure Rust: the `image` crate's encoder).
///
/// Errors: [`Error::InvalidInput`] for a path not ending in `.gif`, no frames, a frame [`views`]
/// would refuse, or a size outside 16–16384 pixels; [`Error::Plot`] when drawing or encoding
/// fails; [`Error::Io`] when the file cannot be written.
pub fn animation(
    path: impl AsRef<Path>,
    frames: &[Frame],
    size: (u32, u32),
    delay_ms: u32,
) -> Result<()> {
    let path = path.as_ref();
    if path.extension().and_then(|e| e.to_str()) != Some("gif") {
        return Err(Error::invalid(
            "animation path",
            format!("`{}` must end in .gif", path.display()),
        ));
    }
    if frames.is_empty() {
        return Err(Error::invalid("frames", "nothing to animate"));
    }
    draw::check_size(size)?;
    draw::register_bundled_font(path)?;
    let rendered = frames.iter().enumerate().map(|(k, frame)| {
        let regions = regions(&frame.views)
            .map_err(|e| Error::invalid(format!("frames[{k}]"), e.to_string()))?;
        draw::render_rgb(size, |root| {
            draw_views(root, &frame.title, &frame.views, &regions)
        })
        .map_err(|reason| draw::plot_error(path, reason))
    });
    draw::write_gif(path, size, delay_ms, rendered)
}

/// The axes of each view, after checking its bounds and data are finite.
fn regions(views: &[View]) -> Result<Vec<(Axis, Axis)>> {
    if views.is_empty() {
        return Err(Error::invalid("views", "nothing to draw"));
    }
    let mut regions = Vec::with_capacity(views.len());
    for (i, view) in views.iter().enumerate() {
        let ((x0, x1), (y0, y1)) = view.bounds;
        let x = Axis::fixed(&format!("views[{i}].bounds x"), x0, x1)?;
        let y = Axis::fixed(&format!("views[{i}].bounds y"), y0, y1)?;
        let finite = |(a, b): (f64, f64)| a.is_finite() && b.is_finite();
        if !view
            .segments
            .iter()
            .chain(&view.highlighted)
            .flatten()
            .copied()
            .all(finite)
            || !view.points.iter().copied().all(finite)
        {
            return Err(Error::invalid(
                format!("views[{i}]"),
                "has a segment or point that is not finite",
            ));
        }
        regions.push((x, y));
    }
    Ok(regions)
}

fn draw_views<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    views: &[View],
    regions: &[(Axis, Axis)],
) -> std::result::Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let root = root.titled(title, ("sans-serif", 24)).map_err(e)?;
    let panels = root.split_evenly((1, views.len()));
    for ((panel, view), (x, y)) in panels.iter().zip(views).zip(regions) {
        let width = view.line_width.max(1);
        let line = ShapeStyle::from(draw::colour(0)).stroke_width(width);
        // Equal scale: widen the shorter side of the region to the panel's aspect ratio.
        let (w, h) = panel.dim_in_pixel();
        let (w, h) = (
            f64::from(w.saturating_sub(80).max(1)),
            f64::from(h.saturating_sub(90).max(1)),
        );
        let scale = ((x.hi - x.lo) / w).max((y.hi - y.lo) / h);
        let (cx, cy) = (0.5 * x.lo + 0.5 * x.hi, 0.5 * y.lo + 0.5 * y.hi);
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
        let second = ShapeStyle::from(draw::colour(1)).stroke_width(width);
        chart
            .draw_series(
                view.highlighted
                    .iter()
                    .map(|&[a, b]| PathElement::new([a, b], second)),
            )
            .map_err(e)?;
        chart
            .draw_series(view.points.iter().map(|&p| Circle::new(p, 4, RED.filled())))
            .map_err(e)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A series with far more points than pixels, zig-zagging between 0 and 1 every point (what
    /// a leapfrog energy recorded every step over 1000 orbits looks like), must draw only inside
    /// the plotting area and within the data's rows: wide strokes joined at sharp reversals used
    /// to spike above the frame and over the title.
    /// Sixty series get sixty different colours (`tab10` used to come round after ten).
    #[test]
    fn series_colours_never_repeat() {
        let colours: Vec<_> = (0..60)
            .map(|i| {
                let c = draw::colour(i);
                (c.0, c.1, c.2)
            })
            .collect();
        for (i, a) in colours.iter().enumerate() {
            assert!(
                colours[..i].iter().all(|b| b != a),
                "series {i} repeats colour {a:?}"
            );
        }
    }

    /// An SVG chart carries each noted point's note as a tooltip over the point, after what it
    /// drew, escaped; a PNG of the same chart is written as before.
    #[test]
    fn svg_points_show_their_notes_on_hover() {
        let dir = std::env::temp_dir().join(format!("odyn-hover-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let chart = Chart {
            title: "Spring".into(),
            note: "lower left is better".into(),
            log_x: true,
            log_y: true,
            series: vec![
                Series::line_and_markers("RK4 (dt)", vec![(1e-3, 2.0), (1e-6, 8.0)])
                    .with_notes(vec!["dt = 0.1".into(), "dt < 0.01".into()]),
            ],
            ..Chart::default()
        };
        let svg = dir.join("chart.svg");
        chart.write(&svg, (640, 400)).unwrap();
        let text = std::fs::read_to_string(&svg).unwrap();
        let hovers: Vec<&str> = text.matches("<title>").collect();
        assert_eq!(hovers.len(), 2);
        assert!(text.contains("<title>RK4 (dt): dt = 0.1</title>"));
        assert!(text.contains("<title>RK4 (dt): dt &lt; 0.01</title>"));
        assert!(text.find("<title>").unwrap() > text.find("lower left is better").unwrap());
        assert!(text.trim_end().ends_with("</svg>"));
        chart.write(dir.join("chart.png"), (640, 400)).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn dense_series_draw_only_inside_the_plot_area() {
        let points = (0..200_000)
            .map(|i| (i as f64, f64::from(i % 2 == 1)))
            .collect();
        let chart = Chart {
            title: "zig-zag".into(),
            series: vec![Series::line("zig-zag", points)],
            ..Chart::default()
        };
        let (x, y) = chart.axes().unwrap();
        draw::register_bundled_font(Path::new("test.png")).unwrap();
        let size = (800u32, 500u32);
        let mut area = None;
        let rgb = draw::render_rgb(size, |root| {
            area = Some(chart.draw(root, x, y)?.plot);
            Ok(())
        })
        .unwrap();
        let (columns, rows) = area.unwrap();
        let row_of = |v: f64| rows.start as f64 + (y.hi - v) / (y.hi - y.lo) * (rows.len() as f64);
        let (top, bottom) = (row_of(1.0) - 7.0, row_of(0.0) + 7.0);
        let (r, g, b) = draw::PALETTE[0];
        let mut drawn = 0;
        let mut rows_hit = (i32::MAX, i32::MIN);
        for py in 0..size.1 as i32 {
            for px in 0..columns.end {
                let i = 3 * (py as usize * size.0 as usize + px as usize);
                if rgb[i..i + 3] == [r, g, b] {
                    drawn += 1;
                    assert!(
                        columns.contains(&px) && rows.contains(&py),
                        "pixel ({px}, {py}) outside the plotting area {columns:?} × {rows:?}"
                    );
                    assert!(
                        (top..=bottom).contains(&f64::from(py)),
                        "pixel ({px}, {py}) outside the data's rows {top}..{bottom}"
                    );
                    rows_hit = (rows_hit.0.min(py), rows_hit.1.max(py));
                }
            }
        }
        assert!(drawn > 1000, "the series was drawn ({drawn} pixels)");
        // Both extremes are drawn, not averaged away.
        assert!(f64::from(rows_hit.0) <= row_of(1.0) + 1.0, "{rows_hit:?}");
        assert!(f64::from(rows_hit.1) >= row_of(0.0) - 1.0, "{rows_hit:?}");
    }

    /// Ticks 2·10⁴ apart past 10⁵ used to print as `1e5 1e5 1e5 2e5`: every label must name its
    /// own value.
    #[test]
    fn large_tick_labels_stay_distinct() {
        let labels: Vec<String> = [1e5, 1.2e5, 1.4e5, 2e5, 2.5e-4, -3.75e6]
            .iter()
            .map(|&v| axis_label(v, false))
            .collect();
        assert_eq!(
            labels,
            ["1e5", "1.2e5", "1.4e5", "2e5", "2.5e-4", "-3.75e6"]
        );
    }

    /// An animation is a looping GIF with one frame per [`Frame`], and bad input is refused.
    #[test]
    fn animations_are_gifs_with_every_frame() {
        use image::AnimationDecoder;
        let dir = std::env::temp_dir().join(format!("odyn-gif-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let frame = |k: usize| Frame {
            title: format!("frame {k}"),
            views: vec![View {
                title: "square".into(),
                segments: vec![[(0.0, 0.0), (k as f64, 1.0)]],
                points: vec![(k as f64, 1.0)],
                bounds: ((0.0, 3.0), (0.0, 2.0)),
                ..View::default()
            }],
        };
        let frames: Vec<Frame> = (0..3).map(frame).collect();
        let path = dir.join("a.gif");
        animation(&path, &frames, (120, 80), 50).unwrap();
        let file = std::fs::File::open(&path).unwrap();
        let decoded = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(file))
            .unwrap()
            .into_frames()
            .collect_frames()
            .unwrap();
        assert_eq!(decoded.len(), 3);
        assert_eq!(decoded[0].buffer().dimensions(), (120, 80));
        assert_eq!(decoded[1].delay().numer_denom_ms(), (50, 1));
        assert!(animation(dir.join("a.png"), &frames, (120, 80), 50).is_err());
        assert!(animation(&path, &[], (120, 80), 50).is_err());
        let mut bad = frame(0);
        bad.views[0].points[0].0 = f64::NAN;
        assert!(animation(&path, &[bad], (120, 80), 50).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn decimation_keeps_order_and_extremes() {
        let points: Vec<(f64, f64)> = (0..1000)
            .map(|i| (i as f64 / 1000.0, (i as f64).sin()))
            .collect();
        let drawn = draw::decimate(&points, (0.0, 1.0), 10);
        assert!(drawn.len() <= 40, "{}", drawn.len());
        assert!(drawn.windows(2).all(|w| w[0].0 <= w[1].0));
        let max = |p: &[(f64, f64)]| p.iter().map(|p| p.1).fold(f64::MIN, f64::max);
        let min = |p: &[(f64, f64)]| p.iter().map(|p| p.1).fold(f64::MAX, f64::min);
        assert_eq!(max(&drawn), max(&points));
        assert_eq!(min(&drawn), min(&points));
        assert_eq!(drawn.first(), points.first());
        assert_eq!(drawn.last(), points.last());
    }
}
