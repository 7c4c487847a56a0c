//! To-scale views of particle scenes: panels of segments and points, as an image or an animated
//! GIF.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::Axis;
use super::draw;
use crate::{Error, Result};

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
/// segment or point that is not finite, or a path or size
/// [`Chart::write`](super::Chart::write) would refuse.
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
    draw::prepare_animation(path, frames.len(), "frames", size)?;
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
