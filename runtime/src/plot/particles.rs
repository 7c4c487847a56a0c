//! Particles coloured by group (a body, a material), drawn to scale: an image, or the frames
//! of an animated GIF — the pictures of SPH, FLIP and MPM runs.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::Axis;
use super::draw;
use crate::{Error, Result};

/// One picture of particles: groups of points, each in its colour with its label, and an
/// outline (the walls), in a fixed region.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Particles {
    /// Title over the picture (`t = 0.25 s`).
    pub title: String,
    /// The groups: a label for the legend and the points, group k in colour k of the chart
    /// palette (`tab10`: blue, orange, green, red, …).
    pub groups: Vec<(String, Vec<(f64, f64)>)>,
    /// Dot radius in pixels (0, the default, draws 1).
    pub radius: u32,
    /// Segments drawn in black under the points (walls, a box).
    pub outline: Vec<[(f64, f64); 2]>,
    /// The region shown, ((x₀, x₁), (y₀, y₁)), equal scale on both axes; keep it fixed across
    /// frames so motion shows.
    pub bounds: ((f64, f64), (f64, f64)),
}

/// Draws `picture` and writes it atomically to `path` (`.png` or `.svg`) at `size` pixels.
///
/// Errors: [`Error::InvalidInput`] for bounds that are not a finite range, a point or segment
/// that is not finite, or a path or size [`Chart::write`](super::Chart::write) would refuse;
/// [`Error::Plot`] or [`Error::Io`] when drawing or writing fails.
pub fn particles(path: impl AsRef<Path>, picture: &Particles, size: (u32, u32)) -> Result<()> {
    let path = path.as_ref();
    draw::image_kind(path)?;
    let axes = check(picture)?;
    draw::write_image(
        path,
        size,
        |root| draw_particles(root, picture, &axes),
        |root| draw_particles(root, picture, &axes).map(|()| String::new()),
    )
}

/// Draws each picture as [`particles`] would and writes them atomically to `path` as a looping
/// animated GIF, `delay_ms` a frame.
///
/// Errors: [`Error::InvalidInput`] for a path not ending in `.gif`, no pictures, a picture
/// [`particles`] would refuse, or a size outside 16–16384 pixels; [`Error::Plot`] or
/// [`Error::Io`] when drawing, encoding or writing fails.
pub fn particle_animation(
    path: impl AsRef<Path>,
    pictures: &[Particles],
    size: (u32, u32),
    delay_ms: u32,
) -> Result<()> {
    let path = path.as_ref();
    draw::prepare_animation(path, pictures.len(), "pictures", size)?;
    let rendered = pictures.iter().enumerate().map(|(k, picture)| {
        let axes =
            check(picture).map_err(|e| Error::invalid(format!("pictures[{k}]"), e.to_string()))?;
        draw::render_rgb(size, |root| draw_particles(root, picture, &axes))
            .map_err(|reason| draw::plot_error(path, reason))
    });
    draw::write_gif(path, size, delay_ms, rendered)
}

/// The axes of a picture, after checking its bounds and data are finite.
fn check(picture: &Particles) -> Result<(Axis, Axis)> {
    let ((x0, x1), (y0, y1)) = picture.bounds;
    let x = Axis::fixed("bounds x", x0, x1)?;
    let y = Axis::fixed("bounds y", y0, y1)?;
    let finite = |&(a, b): &(f64, f64)| a.is_finite() && b.is_finite();
    if !picture.groups.iter().all(|(_, p)| p.iter().all(finite))
        || !picture.outline.iter().flatten().all(finite)
    {
        return Err(Error::invalid(
            "particles",
            "a point or segment is not finite",
        ));
    }
    Ok((x, y))
}

fn draw_particles<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    picture: &Particles,
    (x, y): &(Axis, Axis),
) -> std::result::Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    // Equal scale: widen the shorter side of the region to the drawing's aspect ratio.
    let (w, h) = root.dim_in_pixel();
    let (w, h) = (
        f64::from(w.saturating_sub(80).max(1)),
        f64::from(h.saturating_sub(90).max(1)),
    );
    let scale = ((x.hi - x.lo) / w).max((y.hi - y.lo) / h);
    let (cx, cy) = (0.5 * (x.lo + x.hi), 0.5 * (y.lo + y.hi));
    let (hx, hy) = (0.5 * scale * w, 0.5 * scale * h);
    let mut chart = ChartBuilder::on(root)
        .caption(&picture.title, ("sans-serif", 22))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(cx - hx..cx + hx, cy - hy..cy + hy)
        .map_err(e)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("x (m)")
        .y_desc("y (m)")
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(e)?;
    let wall = ShapeStyle::from(BLACK).stroke_width(2);
    chart
        .draw_series(
            picture
                .outline
                .iter()
                .map(|&[a, b]| PathElement::new([a, b], wall)),
        )
        .map_err(e)?;
    let radius = picture.radius.max(1);
    for (k, (label, points)) in picture.groups.iter().enumerate() {
        let colour = draw::colour(k);
        chart
            .draw_series(
                points
                    .iter()
                    .map(|&p| Circle::new(p, radius, colour.filled())),
            )
            .map_err(e)?
            .label(label)
            .legend(move |(px, py)| Circle::new((px + 8, py), 5, colour.filled()));
    }
    if picture.groups.iter().any(|(label, _)| !label.is_empty()) {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 14))
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(e)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A picture and an animation are written; a non-finite point, an empty animation and a
    /// wrong extension are typed errors, and nothing is left behind by them.
    #[test]
    fn pictures_are_written_and_bad_ones_refused() {
        let dir = std::env::temp_dir().join(format!("odyn-particles-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let picture = Particles {
            title: "two groups".into(),
            groups: vec![
                ("water".into(), vec![(0.1, 0.1), (0.2, 0.1)]),
                ("snow".into(), vec![(0.5, 0.5)]),
            ],
            radius: 2,
            outline: vec![[(0.0, 0.0), (1.0, 0.0)]],
            bounds: ((0.0, 1.0), (0.0, 1.0)),
        };
        particles(dir.join("p.png"), &picture, (200, 200)).unwrap();
        particle_animation(
            dir.join("p.gif"),
            &[picture.clone(), picture.clone()],
            (64, 64),
            50,
        )
        .unwrap();
        assert!(dir.join("p.png").metadata().unwrap().len() > 0);
        assert!(dir.join("p.gif").metadata().unwrap().len() > 0);
        let mut bad = picture.clone();
        bad.groups[0].1.push((f64::NAN, 0.0));
        assert!(matches!(
            particles(dir.join("bad.png"), &bad, (200, 200)),
            Err(Error::InvalidInput { .. })
        ));
        assert!(!dir.join("bad.png").exists());
        assert!(particle_animation(dir.join("none.gif"), &[], (64, 64), 50).is_err());
        assert!(particles(dir.join("p.jpg"), &picture, (200, 200)).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
