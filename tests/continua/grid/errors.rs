//! Bad grids and replaced states of another size are typed errors.

use odyn::grid::{Boundary, Grid};
use odyn::integrators::Rk4;
use odyn::{Error, Model, Simulate, State, Stepper};

use super::{Heat, gray_scott, heat};

/// Bad input is a typed error: a grid whose values do not fill it, a periodic side too short
/// for distinct neighbours, more cells than memory holds, and fields of different sizes in one
/// model.
#[test]
fn bad_grids_are_typed_errors() {
    let wrong = Grid::new(4, 4, Boundary::Neumann, vec![0.0; 15]).unwrap_err();
    assert!(
        wrong.to_string().contains("16 cells but was given 15"),
        "{wrong}"
    );
    let short = Grid::new(2, 8, Boundary::Periodic, vec![0.0; 16]).unwrap_err();
    assert!(short.to_string().contains("at least 3"), "{short}");
    let nan = Grid::new(3, 3, Boundary::Dirichlet(f64::NAN), vec![0.0; 9]).unwrap_err();
    assert!(nan.to_string().contains("finite"), "{nan}");
    // nx·ny overflowing usize used to panic ("capacity overflow") in `from_fn`.
    let huge = Grid::from_fn(usize::MAX / 2, 4, Boundary::Neumann, |_, _| 0.0).unwrap_err();
    assert!(huge.to_string().contains("more cells"), "{huge}");
    let huge = Grid::new(usize::MAX, 2, Boundary::Neumann, vec![]).unwrap_err();
    assert!(huge.to_string().contains("more cells"), "{huge}");
    // 2⁵⁰ cells (8 PB, beyond any address space) used to abort the process.
    let huge = Grid::from_fn(1 << 40, 1 << 10, Boundary::Neumann, |_, _| 0.0).unwrap_err();
    assert!(huge.to_string().contains("cannot be allocated"), "{huge}");
    let mut model = gray_scott(6, Boundary::Periodic);
    model.v = Grid::new(5, 6, Boundary::Periodic, vec![0.0; 30]).unwrap();
    let error = model.simulate().steps(1).run().unwrap_err();
    assert!(
        matches!(error, odyn::Error::BadModel { .. }) && error.to_string().contains("5×6"),
        "{error}"
    );
}

/// Replacing the state through `Stepper::state_mut` by one of another size used to step on
/// silently, the state quietly back at the old size; a grid of the same number of cells but
/// another shape stepped as if the model's grid were that shape.
#[test]
fn a_replaced_state_of_another_size_is_a_typed_error() {
    let model = heat(8);
    let mut stepper = Stepper::<Heat, Rk4<_>>::new(&model, model.state(), 0.0, 1e-4).unwrap();
    stepper.step().unwrap();
    *stepper.state_mut() = heat(6).state();
    let error = stepper.step().unwrap_err();
    assert!(
        matches!(&error, Error::InvalidInput { field, .. } if field == "state")
            && error.to_string().contains("36 components")
            && error.to_string().contains("64"),
        "{error}"
    );
    assert_eq!(stepper.steps(), 1);

    // 4×16 cells in place of 8×8: as many values, another grid.
    let wide = Heat {
        u: Grid::from_fn(4, 16, Boundary::Dirichlet(0.0), |_, _| 1.0).unwrap(),
        ..heat(8)
    };
    *stepper.state_mut() = wide.state();
    let error = stepper.step().unwrap_err();
    assert!(error.to_string().contains("4×16"), "{error}");

    // Values changed in place go on stepping.
    *stepper.state_mut() = model.state();
    stepper.state_mut().as_mut_slice()[9] = 2.0;
    stepper.step().unwrap();
    assert_eq!(stepper.steps(), 2);
}
