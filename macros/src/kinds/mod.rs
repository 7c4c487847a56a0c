//! Model kinds: one front-end each.
pub(crate) mod grid;
