//! Colour-mapped images of scalar fields on a grid (smoke density, concentrations), as PNG
//! frames and animated GIFs: the field drawn pixel by pixel, with a caption (title, field name,
//! time) and a colour bar drawn by plotters beside it unless the style asks for bare frames.

use std::path::Path;

use plotters::prelude::*;

use super::chart::axis_label;
use super::draw;
use crate::{Error, Result};

/// A scalar field on a `width`×`height` grid, row by row from the bottom (y up): value
/// (i, j) is `values[i + j·width]`, with what its caption says about it.
///
/// ```
/// use odyn_runtime::plot::Field;
/// let values = vec![0.0; 4 * 3];
/// let field = Field::new(4, 3, &values).titled("Gray–Scott, coral").named("u").at_time(10.0);
/// assert_eq!(field.caption(), "Gray–Scott, coral: u at t = 10");
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Field<'a> {
    /// Cells across.
    pub width: usize,
    /// Cells up.
    pub height: usize,
    /// The values, `width·height` of them.
    pub values: &'a [f64],
    /// What the image shows (empty: no title).
    pub title: &'a str,
    /// The field's name, such as `u` (empty: none).
    pub name: &'a str,
    /// The time of the state the field was read from.
    pub time: Option<f64>,
}

impl<'a> Field<'a> {
    /// A `width`×`height` field with no caption.
    pub fn new(width: usize, height: usize, values: &'a [f64]) -> Self {
        Field {
            width,
            height,
            values,
            title: "",
            name: "",
            time: None,
        }
    }

    /// With a title.
    pub fn titled(self, title: &'a str) -> Self {
        Field { title, ..self }
    }

    /// With the field's name.
    pub fn named(self, name: &'a str) -> Self {
        Field { name, ..self }
    }

    /// With the time of the state.
    pub fn at_time(self, time: f64) -> Self {
        Field {
            time: Some(time),
            ..self
        }
    }

    /// The caption line: `title: name at t = time`, leaving out what is not given.
    pub fn caption(&self) -> String {
        let time = self.time.map(|t| format!("t = {}", axis_label(t, false)));
        let detail = match (self.name, time) {
            ("", None) => String::new(),
            (name, None) => name.to_owned(),
            ("", Some(time)) => time,
            (name, Some(time)) => format!("{name} at {time}"),
        };
        match (self.title, detail.as_str()) {
            (title, "") => title.to_owned(),
            ("", detail) => detail.to_owned(),
            (title, detail) => format!("{title}: {detail}"),
        }
    }
}

/// How a [`Field`] is coloured, scaled and framed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldStyle {
    /// Values mapped to the ends of the colour map (below and above are clamped; default
    /// (0, 1)).
    pub range: (f64, f64),
    /// Pixels per cell along each side (default 4).
    pub scale: u32,
    /// Only the field's pixels: no caption line and no colour bar (default false).
    pub bare: bool,
}

impl Default for FieldStyle {
    fn default() -> Self {
        FieldStyle {
            range: (0.0, 1.0),
            scale: 4,
            bare: false,
        }
    }
}

/// Writes `field` as a colour-mapped PNG, atomically.
///
/// Errors: as [`field_animation`].
pub fn field_image(path: impl AsRef<Path>, field: Field<'_>, style: FieldStyle) -> Result<()> {
    let path = path.as_ref();
    if path.extension().and_then(|e| e.to_str()) != Some("png") {
        return Err(Error::invalid(
            "field image path",
            format!("`{}` must end in .png", path.display()),
        ));
    }
    let (rgb, size) = render(path, field, style)?;
    let png = draw::encode_png(&rgb, size).map_err(|r| draw::plot_error(path, r))?;
    crate::output::write_atomic(path, &png)
}

/// Writes one colour-mapped frame per field as a looping animated GIF, `delay_ms` a frame.
///
/// Errors: [`Error::InvalidInput`] for a path with the wrong extension, no frames, a field whose
/// width·height overflows or is not its value count, a range that is not finite and
/// increasing, a scale of 0 or an image side over 16384 pixels; [`Error::Plot`] when encoding
/// fails; [`Error::Io`] when the file cannot be written.
pub fn field_animation(
    path: impl AsRef<Path>,
    frames: &[Field<'_>],
    style: FieldStyle,
    delay_ms: u32,
) -> Result<()> {
    let path = path.as_ref();
    if path.extension().and_then(|e| e.to_str()) != Some("gif") {
        return Err(Error::invalid(
            "field animation path",
            format!("`{}` must end in .gif", path.display()),
        ));
    }
    let Some(first) = frames.first() else {
        return Err(Error::invalid("frames", "nothing to animate"));
    };
    let (first, size) = render(path, *first, style)?;
    let rest = frames[1..].iter().map(|field| {
        let (rgb, frame_size) = render(path, *field, style)?;
        if frame_size != size {
            return Err(Error::invalid(
                "frames",
                "every field of an animation must have the same grid",
            ));
        }
        Ok(rgb)
    });
    draw::write_gif(path, size, delay_ms, std::iter::once(Ok(first)).chain(rest))
}

/// RGB pixels of the image of `field` (top row first) and its size: the field alone for a
/// bare style, otherwise with its caption and colour bar.
fn render(path: &Path, field: Field<'_>, style: FieldStyle) -> Result<(Vec<u8>, (u32, u32))> {
    let (pixels, size) = pixels(field, style)?;
    if style.bare {
        Ok((pixels, size))
    } else {
        annotate(path, field, style, &pixels, size)
    }
}

/// RGB pixels of `field` alone (top row first) and their size.
fn pixels(field: Field<'_>, style: FieldStyle) -> Result<(Vec<u8>, (u32, u32))> {
    let Field {
        width,
        height,
        values,
        ..
    } = field;
    let Some(cells) = width.checked_mul(height) else {
        return Err(Error::invalid(
            "field",
            format!(
                "{width}×{height}: width·height overflows, so no list of values can match; give \
                 the grid's sides in cells"
            ),
        ));
    };
    if width == 0 || height == 0 || values.len() != cells {
        return Err(Error::invalid(
            "field",
            format!("{} values for a {width}×{height} grid", values.len()),
        ));
    }
    let (lo, hi) = style.range;
    if !(lo.is_finite() && hi.is_finite() && lo < hi) {
        return Err(Error::invalid(
            "range",
            format!("must be finite and increasing, got ({lo:?}, {hi:?})"),
        ));
    }
    let scale = style.scale as usize;
    let (w, h) = (width.saturating_mul(scale), height.saturating_mul(scale));
    if scale == 0 || w > 16_384 || h > 16_384 {
        return Err(Error::invalid(
            "scale",
            format!(
                "{width}×{height} cells at {scale} pixels each: each side must be 1 to 16384 pixels"
            ),
        ));
    }
    let mut rgb = vec![0u8; w * h * 3];
    for (row, line) in rgb.chunks_exact_mut(w * 3).enumerate() {
        let j = height - 1 - row / scale;
        for (col, pixel) in line.chunks_exact_mut(3).enumerate() {
            let value = values[col / scale + j * width];
            pixel.copy_from_slice(&inferno((value - lo) / (hi - lo)));
        }
    }
    Ok((rgb, (w as u32, h as u32)))
}

/// Pixels between the image's edge and what is drawn.
const MARGIN: u32 = 10;
/// Height of the caption line above the field.
const CAPTION: u32 = 30;
/// The colour bar: its gap from the field, its width, and the room for its labels.
const BAR: (u32, u32, u32) = (12, 14, 84);

/// The field's `pixels` (`w`×`h`) on a white canvas with the caption above and the colour bar,
/// labelled at its ends and middle, to the right.
fn annotate(
    path: &Path,
    field: Field<'_>,
    style: FieldStyle,
    pixels: &[u8],
    (w, h): (u32, u32),
) -> Result<(Vec<u8>, (u32, u32))> {
    let caption = field.caption();
    let (gap, bar, labels) = BAR;
    // DejaVu Sans at 16 px averages under 9 px a character.
    let text = 9 * caption.chars().count() as u32 + 2 * MARGIN;
    let size = (
        (MARGIN + w + gap + bar + labels).max(text),
        CAPTION + h + MARGIN,
    );
    if size.0 > 16_384 || size.1 > 16_384 {
        return Err(Error::invalid(
            "scale",
            format!(
                "{}×{} pixels with the caption and colour bar: each side must be at most 16384 \
                 (a smaller scale, or a bare style)",
                size.0, size.1
            ),
        ));
    }
    let (width, stride) = (size.0 as usize, w as usize * 3);
    let mut rgb = vec![255u8; width * size.1 as usize * 3];
    let bar_x = (MARGIN + w + gap) as usize;
    for (row, line) in pixels.chunks_exact(stride).enumerate() {
        let start = ((CAPTION as usize + row) * width + MARGIN as usize) * 3;
        rgb[start..start + stride].copy_from_slice(line);
        // The colour bar, highest value at the top, level with the field.
        let colour = inferno(1.0 - (row as f64 + 0.5) / h as f64);
        let start = ((CAPTION as usize + row) * width + bar_x) * 3;
        for pixel in rgb[start..start + bar as usize * 3].chunks_exact_mut(3) {
            pixel.copy_from_slice(&colour);
        }
    }
    draw::register_bundled_font(path)?;
    let (lo, hi) = style.range;
    let ticks: &[(f64, f64)] = if h >= 48 {
        &[(0.0, hi), (0.5, 0.5 * (lo + hi)), (1.0, lo)]
    } else {
        &[(0.0, hi), (1.0, lo)]
    };
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let fail = |e: DrawingAreaErrorKind<_>| draw::plot_error(path, e.to_string());
        let font = |px| ("sans-serif", px).into_font();
        root.draw(&Text::new(caption, (MARGIN as i32, 7), font(16)))
            .map_err(fail)?;
        let (x, top) = ((bar_x as u32 + bar) as i32, CAPTION as i32);
        for &(at, value) in ticks {
            let y = top + (at * (h - 1) as f64).round() as i32;
            root.draw(&PathElement::new(vec![(x, y), (x + 4, y)], BLACK))
                .map_err(fail)?;
            root.draw(&Text::new(
                axis_label(value, false),
                (x + 7, (y - 7).clamp(top - 4, top + h as i32 - 10)),
                font(13),
            ))
            .map_err(fail)?;
        }
        root.present().map_err(fail)?;
    }
    Ok((rgb, size))
}

/// Matplotlib's "inferno" colour map (van der Walt & Smith, 2015), sampled at nine points and
/// interpolated linearly: perceptually uniform, black to yellow. NaN maps to black.
fn inferno(x: f64) -> [u8; 3] {
    const STOPS: [[f64; 3]; 9] = [
        [0.0, 0.0, 4.0],
        [31.0, 12.0, 72.0],
        [85.0, 15.0, 109.0],
        [136.0, 34.0, 106.0],
        [186.0, 54.0, 85.0],
        [227.0, 89.0, 51.0],
        [249.0, 140.0, 10.0],
        [249.0, 201.0, 50.0],
        [252.0, 255.0, 164.0],
    ];
    let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) } * 8.0;
    let k = (x as usize).min(7);
    let t = x - k as f64;
    std::array::from_fn(|c| (STOPS[k][c] + t * (STOPS[k + 1][c] - STOPS[k][c])).round() as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The annotated image is the field, unchanged, with a caption above it and the colour bar
    /// (highest value at the top) beside it; a bare style gives the field's pixels alone.
    #[test]
    fn annotated_fields_keep_their_pixels_and_add_a_colour_bar() {
        let values: Vec<f64> = (0..8 * 6).map(|k| (k % 8) as f64 / 7.0).collect();
        let field = Field::new(8, 6, &values)
            .titled("ramp")
            .named("u")
            .at_time(0.5);
        let style = FieldStyle {
            range: (0.0, 1.0),
            scale: 10,
            bare: false,
        };
        let path = Path::new("ramp.png");
        let (bare, (w, h)) = render(
            path,
            field,
            FieldStyle {
                bare: true,
                ..style
            },
        )
        .unwrap();
        assert_eq!((w, h), (80, 60));
        let (rgb, size) = render(path, field, style).unwrap();
        let (gap, bar, labels) = BAR;
        assert_eq!(
            size,
            (MARGIN + 80 + gap + bar + labels, CAPTION + 60 + MARGIN)
        );
        let pixel = |x: u32, y: u32| {
            let i = 3 * (y as usize * size.0 as usize + x as usize);
            [rgb[i], rgb[i + 1], rgb[i + 2]]
        };
        for y in 0..h {
            for x in 0..w {
                let i = 3 * (y * w + x) as usize;
                assert_eq!(pixel(MARGIN + x, CAPTION + y), bare[i..i + 3]);
            }
        }
        let bar_x = MARGIN + w + gap + bar / 2;
        assert_eq!(pixel(bar_x, CAPTION), inferno(1.0 - 0.5 / 60.0));
        assert_eq!(pixel(bar_x, CAPTION + 59), inferno(0.5 / 60.0));
        // The caption drew something dark on the white band above the field.
        let dark = (0..size.0)
            .flat_map(|x| (0..CAPTION).map(move |y| (x, y)))
            .filter(|&(x, y)| pixel(x, y)[0] < 128)
            .count();
        assert!(dark > 50, "{dark} dark caption pixels");
        assert_eq!(field.caption(), "ramp: u at t = 0.5");
    }
}
