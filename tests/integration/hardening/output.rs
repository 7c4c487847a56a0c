//! Charts, trajectories and files that cannot be written, and numbers in error messages.

use odyn::plot::{Chart, Series, View, views};
use odyn::prelude::*;

use super::{invalid_field, scratch};
use crate::common::Spring;

/// Charts refuse what they cannot draw with typed errors, never a panic or a hang: empty or
/// all-NaN data, values near ±1e308 (padding used to overflow to ±∞ and hang), views with
/// infinite or NaN bounds (a NaN bound used to panic and leave the temporary file behind).
#[test]
fn charts_refuse_what_they_cannot_draw() {
    let path = scratch("charts", "chart.png");
    let chart = |points: Vec<(f64, f64)>| Chart {
        series: vec![Series::line("s", points)],
        ..Chart::default()
    };
    assert!(matches!(
        chart(vec![]).write(&path, (400, 300)),
        Err(Error::InvalidInput { .. })
    ));
    assert!(matches!(
        chart(vec![(f64::NAN, f64::NAN)]).write(&path, (400, 300)),
        Err(Error::InvalidInput { .. })
    ));
    assert!(matches!(
        chart(vec![(0.0, -1.7e308), (1.0, 1.7e308)]).write(&path, (400, 300)),
        Err(Error::InvalidInput { .. })
    ));
    // A constant series is fine: its axis is widened around the value.
    chart(vec![(0.0, 3.0), (1.0, 3.0)])
        .write(&path, (400, 300))
        .unwrap();
    for bounds in [
        ((0.0, f64::INFINITY), (0.0, 1.0)),
        ((0.0, 1.0), (f64::NAN, 1.0)),
        ((1.0, 0.0), (0.0, 1.0)),
    ] {
        let view = View {
            bounds,
            segments: vec![[(0.0, 0.0), (1.0, 1.0)]],
            ..View::default()
        };
        let file = scratch("charts", "view.png");
        assert!(matches!(
            views(&file, "t", &[view], (400, 300)),
            Err(Error::InvalidInput { .. })
        ));
        assert!(!file.exists());
    }
    assert!(matches!(
        views(scratch("charts", "none.png"), "t", &[], (400, 300)),
        Err(Error::InvalidInput { .. })
    ));
    let leftovers: Vec<_> = std::fs::read_dir(path.parent().unwrap())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

/// Writing a trajectory whose samples were emptied is a typed error (it was an index panic).
#[test]
fn an_emptied_trajectory_is_a_typed_error() {
    let mut run = Spring::released().simulate().steps(3).run().unwrap();
    run.samples.clear();
    assert_eq!(
        invalid_field(run.write_csv(scratch("emptied", "empty.csv"))),
        "trajectory"
    );
    assert!(run.at(0.0).is_err());
}

/// A write that cannot happen is a clean `Io` error for a PNG as for a CSV; a read-only target
/// is refused rather than replaced; a symlink is followed (the file it points to is replaced,
/// the link stays); no temporary survives.
#[cfg(unix)]
#[test]
fn output_files_respect_permissions_and_links() {
    use std::os::unix::fs::PermissionsExt;
    let run = Spring::released().simulate().steps(3).run().unwrap();
    let dir = scratch("outputs", "locked");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o555)).unwrap();
    let root = std::fs::File::create(dir.join("probe")).is_ok();
    if !root {
        // (As root every write succeeds, so only an unprivileged run can see the refusal.)
        let png = odyn::plot::energy(dir.join("e.png"), &[("s", &run)]);
        assert!(matches!(png, Err(Error::Io { .. })), "{png:?}");
        assert!(matches!(
            run.write_csv(dir.join("e.csv")),
            Err(Error::Io { .. })
        ));
    }
    std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o755)).unwrap();
    let readonly = scratch("outputs", "readonly.csv");
    std::fs::write(&readonly, "keep me").unwrap();
    std::fs::set_permissions(&readonly, std::fs::Permissions::from_mode(0o444)).unwrap();
    assert!(matches!(run.write_csv(&readonly), Err(Error::Io { .. })));
    assert_eq!(std::fs::read_to_string(&readonly).unwrap(), "keep me");
    let target = scratch("outputs", "target.csv");
    std::fs::write(&target, "old").unwrap();
    let link = scratch("outputs", "link.csv");
    let _ = std::fs::remove_file(&link);
    std::os::unix::fs::symlink(&target, &link).unwrap();
    run.write_csv(&link).unwrap();
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert!(
        std::fs::read_to_string(&target)
            .unwrap()
            .starts_with("method,")
    );
}

/// Numbers in error messages print in their shortest exact form (`1e-300`), never as hundreds of
/// digits.
#[test]
fn error_messages_print_numbers_compactly() {
    let error = Spring::released()
        .simulate()
        .dt(-1e-300)
        .steps(1)
        .run()
        .unwrap_err();
    let text = error.to_string();
    assert!(text.contains("-1e-300"), "{text}");
    assert!(text.len() < 120, "{text}");
}
