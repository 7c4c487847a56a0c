//! The plots' unit tests: colours, hover notes, clipping, tick labels, animations, decimation.

use std::path::Path;

use super::chart::axis_label;
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
