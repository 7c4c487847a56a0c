//! The tests of the models `#[system]` generates — their Jacobians through every branch, loop and
//! helper, parameters and sensitivities, fitting, dual numbers, differential–algebraic models —
//! one module per topic, in one test binary (the runtime's
//! tests are the other, `tests/integration/`). Run one topic with
//! `cargo test -p odyn-model-tests dae::`.
//!
//! A new topic is `tests/models/NAME.rs`, listed below (a folder `NAME/` of files by subtopic
//! once it passes 600 lines); it reaches the shared models with `use crate::common;`.

#[path = "../common/mod.rs"]
mod common;

mod big_models;
mod const_generic;
mod control_flow;
mod dae;
mod differences;
mod dual;
mod dual_rules;
mod fit;
mod helpers;
mod jacobian;
mod parameters;
mod sensitivity_events;
mod shapes;
mod state;
mod trajectory;
mod unrolled;
