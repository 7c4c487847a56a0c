//! Colour-mapped images of scalar fields on a grid (smoke density, concentrations), as PNG
//! frames and animated GIFs, drawn pixel by pixel with the `image` crate.

use std::path::Path;

use super::draw;
use crate::{Error, Result};

/// A scalar field on a `width`×`height` grid, row by row from the bottom (y up): value
/// (i, j) is `values[i + j·width]`.
#[derive(Clone, Copy, Debug)]
pub struct Field<'a> {
    /// Cells across.
    pub width: usize,
    /// Cells up.
    pub height: usize,
    /// The values, `width·height` of them.
    pub values: &'a [f64],
}

/// How a [`Field`] is coloured and scaled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldStyle {
    /// Values mapped to the ends of the colour map (below and above are clamped).
    pub range: (f64, f64),
    /// Pixels per cell along each side.
    pub scale: u32,
}

impl Default for FieldStyle {
    fn default() -> Self {
        FieldStyle {
            range: (0.0, 1.0),
            scale: 4,
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
    let (rgb, size) = render(field, style)?;
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
    // The image size of the first frame (an oversized one is refused by `render` below).
    let side = |cells: usize| {
        u32::try_from(cells.saturating_mul(style.scale as usize)).unwrap_or(u32::MAX)
    };
    let size = (side(first.width), side(first.height));
    let rendered = frames.iter().map(|field| {
        let (rgb, frame_size) = render(*field, style)?;
        if frame_size != size {
            return Err(Error::invalid(
                "frames",
                "every field of an animation must have the same grid",
            ));
        }
        Ok(rgb)
    });
    draw::write_gif(path, size, delay_ms, rendered)
}

/// RGB pixels of `field` (top row first) and the image size.
fn render(field: Field<'_>, style: FieldStyle) -> Result<(Vec<u8>, (u32, u32))> {
    let Field {
        width,
        height,
        values,
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
