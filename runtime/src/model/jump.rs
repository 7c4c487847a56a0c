//! [`Jump`]: a change event as a model sees it when it completes the change.

/// A change event as [`crate::Model::complete_change`] sees it: the event's condition (none for
/// a time event, whose time does not move with the state) and its change.
pub struct Jump<'e, S> {
    /// The event's name, for errors.
    pub name: &'e str,
    /// g(t, y), whose zero the event is.
    #[allow(clippy::type_complexity)]
    pub condition: Option<&'e (dyn Fn(f64, &S) -> f64 + Send + Sync)>,
    /// The change applied to the state.
    pub change: &'e (dyn Fn(f64, &mut S) + Send + Sync),
}
