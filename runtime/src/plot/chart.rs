//! General charts: labelled line and marker series on linear or logarithmic axes, with notes
//! that an SVG shows on hover.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::Axis;
use super::draw::{self, LegendEntry, PixelRect};
use crate::{Error, Result};

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
    pub(super) fn axes(&self) -> Result<(Axis, Axis)> {
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
    pub(super) fn draw<DB: DrawingBackend>(
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
        // A tick that should be 0 but was reached by adding steps (−2.2e-16) reads 0.
        let tick = |v: f64, log: bool, span: f64| {
            axis_label(
                if !log && v.abs() < 1e-9 * span {
                    0.0
                } else {
                    v
                },
                log,
            )
        };
        let (x_span, y_span) = (x.hi - x.lo, y.hi - y.lo);
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&|v| tick(*v, log_x, x_span))
            .y_label_formatter(&|v| tick(*v, log_y, y_span))
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
pub(super) struct Drawn {
    /// The plotting area's pixel rectangle.
    #[cfg_attr(not(test), expect(dead_code, reason = "read by the chart-bounds test"))]
    pub(super) plot: PixelRect,
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
pub(super) fn axis_label(v: f64, log: bool) -> String {
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
