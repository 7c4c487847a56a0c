//! CSV and plot files: columns, atomic writes, typed errors for bad paths.

use crate::common;

use common::{Lorenz, Spring};
use odyn::prelude::*;
use odyn::{Error, output, plot};

fn runs() -> Vec<Trajectory<common::SpringState>> {
    let spring = Spring {
        x: 1.0,
        v: 0.0,
        k: 1.0,
        b: 0.0,
        m: 1.0,
    };
    [Method::ExplicitEuler, Method::Rk4]
        .iter()
        .map(|&m| {
            spring
                .simulate()
                .integrator(m)
                .dt(0.05)
                .steps(400)
                .run()
                .unwrap()
        })
        .collect()
}

#[test]
fn csv_has_the_lab_columns_and_one_row_per_sample() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("nested/lab.csv");
    let runs = runs();
    output::write_csv(&path, &runs.iter().collect::<Vec<_>>()).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("method,step,t,x,v,energy"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 2 * 401);
    assert_eq!(rows[0], ["explicit_euler", "0", "0.0", "1.0", "0.0", "0.5"]);
    assert_eq!(rows[401][0..2], ["rk4", "0"]);
    // Numbers read back exactly.
    let last: f64 = rows[400][5].parse().unwrap();
    assert_eq!(last, runs[0].last().energy.unwrap());
    // Nothing but the file is left in the directory (the temporary was renamed).
    let entries: Vec<_> = std::fs::read_dir(path.parent().unwrap()).unwrap().collect();
    assert_eq!(entries.len(), 1);
}

#[test]
fn vector_and_energy_free_models_get_their_own_columns() {
    let dir = tempfile::tempdir().unwrap();
    let run = Lorenz::classic().simulate().steps(2).run().unwrap();
    run.write_csv(dir.path().join("lorenz.csv")).unwrap();
    let text = std::fs::read_to_string(dir.path().join("lorenz.csv")).unwrap();
    assert_eq!(text.lines().next(), Some("method,step,t,x,y,z"));
    let kepler = common::Kepler {
        r: Vector2::new(1.0, 0.0),
        v: Vector2::new(0.0, 1.0),
        gm: 1.0,
    };
    let run = kepler.simulate().steps(1).run().unwrap();
    run.write_csv(dir.path().join("kepler.csv")).unwrap();
    let text = std::fs::read_to_string(dir.path().join("kepler.csv")).unwrap();
    assert_eq!(
        text.lines().next(),
        Some("method,step,t,r[0],r[1],v[0],v[1],energy")
    );
}

#[test]
fn an_unwritable_path_is_a_typed_error_and_leaves_nothing_behind() {
    let dir = tempfile::tempdir().unwrap();
    let blocker = dir.path().join("file");
    std::fs::write(&blocker, "not a directory").unwrap();
    let runs = runs();
    let error = runs[0].write_csv(blocker.join("lab.csv")).unwrap_err();
    assert!(matches!(error, Error::Io { .. }), "{error:?}");
    // Writing over a directory fails at the rename; the temporary is removed.
    let target = dir.path().join("taken");
    std::fs::create_dir(&target).unwrap();
    std::fs::write(target.join("keep"), "x").unwrap();
    assert!(matches!(runs[0].write_csv(&target), Err(Error::Io { .. })));
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left.len(), 2, "{left:?}");
}

#[test]
fn plots_are_written_as_png_and_svg() {
    let dir = tempfile::tempdir().unwrap();
    let runs = runs();
    let labelled: Vec<_> = runs.iter().map(|r| (r.method.label(), r)).collect();
    plot::energy(dir.path().join("e.png"), &labelled).unwrap();
    let png = std::fs::read(dir.path().join("e.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let look = plot::EnergyPlot {
        log_y: true,
        relative: true,
        title: "log".into(),
        ..Default::default()
    };
    plot::energy_with(dir.path().join("e.svg"), &labelled, &look).unwrap();
    let svg = std::fs::read_to_string(dir.path().join("e.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("Explicit Euler"));
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
}

#[test]
fn plot_errors_are_typed() {
    let dir = tempfile::tempdir().unwrap();
    let runs = runs();
    let labelled: Vec<_> = runs.iter().map(|r| (r.method.label(), r)).collect();
    let error = plot::energy(dir.path().join("e.jpg"), &labelled).unwrap_err();
    assert!(
        matches!(error, Error::InvalidInput { ref field, .. } if field == "plot path"),
        "{error:?}"
    );
    let lorenz = Lorenz::classic().simulate().steps(2).run().unwrap();
    let error = plot::energy(dir.path().join("l.png"), &[("lorenz", &lorenz)]).unwrap_err();
    assert!(
        error.to_string().contains("defines no `fn energy`"),
        "{error}"
    );
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// A field whose width·height overflows usize used to panic counting its values (in
/// `field_image`, and in `field_animation` even before that, sizing the image); both are input
/// errors naming the field, and nothing is written.
#[test]
fn field_images_refuse_a_grid_whose_size_overflows() {
    let dir = tempfile::tempdir().unwrap();
    let style = plot::FieldStyle::default();
    for (width, height) in [(usize::MAX, 2), (1 << 33, 1 << 33)] {
        let field = plot::Field::new(width, height, &[]);
        for error in [
            plot::field_image(dir.path().join("f.png"), field, style).unwrap_err(),
            plot::field_animation(dir.path().join("f.gif"), &[field], style, 100).unwrap_err(),
        ] {
            assert!(
                matches!(error, Error::InvalidInput { ref field, .. } if field == "field"),
                "{error:?}"
            );
            assert!(error.to_string().contains("overflows"), "{error}");
        }
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}
