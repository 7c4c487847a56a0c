//! Drawing with plotters: backends, line decimation, markers and the legend panel.
//!
//! PNGs are rendered into memory and encoded here, then written by
//! [`crate::output::write_atomic`]: a failure to write is the same clean [`Error::Io`] as for a
//! CSV, and no backend ever touches the file system.

use std::ops::Range;
use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

use crate::output::write_atomic;
use crate::{Error, Result};

/// DejaVu Sans, under the Bitstream Vera licence (see `assets/DejaVuSans-LICENSE.txt`).
const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Matplotlib's `tab10`: distinct on white, and legible to most colour-blind readers.
pub(crate) const PALETTE: [(u8, u8, u8); 10] = [
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

/// The colour of series `i`: `tab10`, then hues a golden angle (137.5°) apart at two
/// lightnesses, dark enough to read on white, so no colour comes round again.
pub(crate) fn colour(i: usize) -> RGBAColor {
    match PALETTE.get(i) {
        Some(&(r, g, b)) => RGBColor(r, g, b).to_rgba(),
        None => {
            let k = (i - PALETTE.len()) as f64;
            let hue = (0.05 + k * 0.381_966_011_250_105).fract();
            let lightness = if i.is_multiple_of(2) { 0.36 } else { 0.5 };
            HSLColor(hue, 0.75, lightness).to_rgba()
        }
    }
}

/// A drawing failure, as plotters reports it.
pub(crate) type Failure = String;

/// Renders `draw` at `size` and writes it atomically to `path` as PNG or SVG (by extension).
/// `draw_svg` returns markup to add on top of what it drew (tooltips).
pub(crate) fn write_image(
    path: &Path,
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<BitMapBackend<'_>, Shift>) -> std::result::Result<(), Failure>,
    draw_svg: impl FnOnce(&DrawingArea<SVGBackend<'_>, Shift>) -> std::result::Result<String, Failure>,
) -> Result<()> {
    let kind = image_kind(path)?;
    check_size(size)?;
    register_bundled_font(path)?;
    match kind {
        ImageKind::Svg => {
            let mut text = String::new();
            let extra = {
                let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
                let extra = draw_svg(&root).map_err(|reason| plot_error(path, reason))?;
                root.present()
                    .map_err(|e| plot_error(path, e.to_string()))?;
                extra
            };
            if let Some(end) = text.rfind("</svg>") {
                text.insert_str(end, &extra);
            }
            write_atomic(path, text.as_bytes())
        }
        ImageKind::Png => {
            let rgb = render_rgb(size, draw).map_err(|reason| plot_error(path, reason))?;
            write_atomic(
                path,
                &encode_png(&rgb, size).map_err(|r| plot_error(path, r))?,
            )
        }
    }
}

/// The image formats a chart can be written as.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ImageKind {
    Png,
    Svg,
}

/// The format `path`'s extension names.
pub(crate) fn image_kind(path: &Path) -> Result<ImageKind> {
    match path.extension().and_then(|e| e.to_str()) {
        Some("png") => Ok(ImageKind::Png),
        Some("svg") => Ok(ImageKind::Svg),
        _ => Err(Error::invalid(
            "plot path",
            format!("`{}` must end in .png or .svg", path.display()),
        )),
    }
}

/// Images from 16 to 16 384 pixels a side.
pub(crate) fn check_size((w, h): (u32, u32)) -> Result<()> {
    if (16..=16_384).contains(&w) && (16..=16_384).contains(&h) {
        Ok(())
    } else {
        Err(Error::invalid(
            "image size",
            format!("{w}×{h} pixels; each side must be 16 to 16384"),
        ))
    }
}

/// Renders into an RGB buffer (3 bytes a pixel, row-major).
pub(crate) fn render_rgb(
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<BitMapBackend<'_>, Shift>) -> std::result::Result<(), Failure>,
) -> std::result::Result<Vec<u8>, Failure> {
    let mut rgb = vec![255u8; size.0 as usize * size.1 as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        draw(&root)?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(rgb)
}

/// PNG bytes of an RGB buffer.
pub(crate) fn encode_png(rgb: &[u8], (w, h): (u32, u32)) -> std::result::Result<Vec<u8>, Failure> {
    use image::ImageEncoder;
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(rgb, w, h, image::ColorType::Rgb8)
        .map_err(|e| e.to_string())?;
    Ok(bytes)
}

/// What every animation checks before drawing a frame: a `.gif` path, at least one frame
/// (`frames`, named `field` in the error), a size of 16–16384 pixels; then the bundled font.
///
/// Errors: [`Error::InvalidInput`]; [`Error::Io`] from registering the font.
pub(crate) fn prepare_animation(
    path: &Path,
    frames: usize,
    field: &str,
    size: (u32, u32),
) -> Result<()> {
    if path.extension().and_then(|e| e.to_str()) != Some("gif") {
        return Err(Error::invalid(
            "animation path",
            format!("`{}` must end in .gif", path.display()),
        ));
    }
    if frames == 0 {
        return Err(Error::invalid(field, "nothing to animate"));
    }
    check_size(size)?;
    register_bundled_font(path)
}

/// Encodes RGB frames (each `size` pixels, from `frames`) as a looping GIF, `delay_ms` a frame,
/// and writes it atomically to `path`. A frame that cannot be rendered stops the encoding with
/// its error.
pub(crate) fn write_gif(
    path: &Path,
    size: (u32, u32),
    delay_ms: u32,
    frames: impl Iterator<Item = Result<Vec<u8>>>,
) -> Result<()> {
    use image::codecs::gif::{GifEncoder, Repeat};
    let fail = |e: image::ImageError| plot_error(path, e.to_string());
    let mut bytes = Vec::new();
    {
        let mut encoder = GifEncoder::new_with_speed(&mut bytes, 30);
        encoder.set_repeat(Repeat::Infinite).map_err(fail)?;
        for rgb in frames {
            let rgba = rgb?
                .chunks_exact(3)
                .flat_map(|p| [p[0], p[1], p[2], 255])
                .collect();
            let buffer = image::RgbaImage::from_raw(size.0, size.1, rgba)
                .ok_or_else(|| plot_error(path, "frame buffer of the wrong size".into()))?;
            let delay = image::Delay::from_numer_denom_ms(delay_ms, 1);
            encoder
                .encode_frame(image::Frame::from_parts(buffer, 0, 0, delay))
                .map_err(fail)?;
        }
    }
    write_atomic(path, &bytes)
}

pub(crate) fn plot_error(path: &Path, reason: String) -> Error {
    Error::Plot {
        path: path.to_path_buf(),
        reason,
    }
}

pub(crate) fn register_bundled_font(path: &Path) -> Result<()> {
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

/// The points of a line as drawn on a plot `columns` pixels wide spanning [x0, x1]: each run of
/// consecutive points that falls in one pixel column becomes its first, lowest, highest and last
/// point, in their original order. The drawn path covers the same pixels and keeps every
/// extreme, but a million-point series costs a few thousand segments.
pub(crate) fn decimate(
    points: &[(f64, f64)],
    (x0, x1): (f64, f64),
    columns: u32,
) -> Vec<(f64, f64)> {
    let scale = f64::from(columns.max(1)) / (x1 - x0);
    let column = |x: f64| ((x - x0) * scale).floor();
    let mut out = Vec::with_capacity(points.len().min(8 * columns as usize + 8));
    let mut run: Vec<(f64, f64)> = Vec::new();
    let flush = |run: &mut Vec<(f64, f64)>, out: &mut Vec<(f64, f64)>| {
        if run.len() <= 4 {
            out.append(run);
            return;
        }
        let (mut lo, mut hi) = (0, 0);
        for (i, p) in run.iter().enumerate() {
            if p.1 < run[lo].1 {
                lo = i;
            }
            if p.1 > run[hi].1 {
                hi = i;
            }
        }
        let mut keep = [0, lo.min(hi), lo.max(hi), run.len() - 1];
        keep.sort_unstable();
        let mut last = usize::MAX;
        for i in keep {
            if i != last {
                out.push(run[i]);
                last = i;
            }
        }
        run.clear();
    };
    for &p in points {
        if let Some(&(x, _)) = run.first()
            && column(x) != column(p.0)
        {
            flush(&mut run, &mut out);
        }
        run.push(p);
    }
    flush(&mut run, &mut out);
    out
}

/// Draws a marker of one of six shapes (chosen by series), about ten pixels across, centred at
/// pixel `at` of `area`.
pub(crate) fn draw_marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    shape: usize,
    at: (i32, i32),
    style: ShapeStyle,
) -> std::result::Result<(), Failure> {
    let filled = style.filled();
    let drawn = match shape % 6 {
        0 => area.draw(&Circle::new(at, 5, filled)),
        1 => area.draw(&(EmptyElement::at(at) + Rectangle::new([(-4, -4), (4, 4)], filled))),
        2 => area.draw(&TriangleMarker::new(at, 6, filled)),
        3 => area.draw(&Cross::new(at, 5, style.stroke_width(2))),
        4 => area.draw(
            &(EmptyElement::at(at) + Polygon::new(vec![(0, -6), (6, 0), (0, 6), (-6, 0)], filled)),
        ),
        _ => area.draw(&Circle::new(at, 5, style.stroke_width(2))),
    };
    drawn.map_err(|e| e.to_string())
}

/// Indices of about `count` points spread evenly along a series of `len` points, shifted by the
/// series' `slot` of `slots` so the markers of two coinciding series do not cover each other.
pub(crate) fn marker_indices(len: usize, count: usize, slot: usize, slots: usize) -> Vec<usize> {
    if len == 0 {
        return Vec::new();
    }
    let count = count.min(len).max(1);
    let shift = (slot % slots.max(1)) as f64 / slots.max(1) as f64;
    let mut indices: Vec<usize> = (0..count)
        .map(|k| (((k as f64 + 0.5 + shift) / count as f64) * len as f64) as usize)
        .map(|i| i.min(len - 1))
        .collect();
    indices.dedup();
    indices
}

/// One legend row: how a series is drawn and its label.
pub(crate) struct LegendEntry<'a> {
    pub(crate) label: &'a str,
    pub(crate) colour: RGBAColor,
    pub(crate) line: bool,
    pub(crate) shape: Option<usize>,
}

/// Width in pixels of a legend panel for `labels` (0 when there are none).
pub(crate) fn legend_width<'a>(labels: impl Iterator<Item = &'a str>, image_width: u32) -> u32 {
    let longest = labels.map(|l| l.chars().count()).max();
    match longest {
        None => 0,
        Some(chars) => (56 + 9 * chars as u32).min(image_width * 2 / 5),
    }
}

/// Draws the legend as a column of rows in its own panel, beside the plot: it never covers data.
pub(crate) fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[LegendEntry<'_>],
    top: i32,
) -> std::result::Result<(), Failure> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let font = ("sans-serif", 15).into_font();
    for (row, entry) in entries.iter().enumerate() {
        let y = top + 24 * row as i32;
        let style = ShapeStyle::from(entry.colour).stroke_width(2);
        if entry.line {
            area.draw(&PathElement::new(vec![(6, y), (40, y)], style))
                .map_err(e)?;
        }
        if let Some(shape) = entry.shape {
            draw_marker(area, shape, (23, y), style)?;
        }
        area.draw(&Text::new(
            entry.label.to_owned(),
            (48, y - 8),
            font.clone(),
        ))
        .map_err(e)?;
    }
    Ok(())
}

/// The pixel rectangle (columns, rows) of a chart's plotting area: what the chart-bounds test
/// checks drawn pixels against.
pub(crate) type PixelRect = (Range<i32>, Range<i32>);
