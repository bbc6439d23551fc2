//! Storage for a unit's saved state, used by the master to roll units back.

use crate::unit::UnitError;
use std::any::Any;

/// An opaque slot that holds one saved state of one unit.
///
/// The master keeps one slot per unit and reuses it at every synchronisation step;
/// [`StateSlot::store`] uses `clone_from`, so a state type whose `Clone` implements
/// `clone_from` field by field allocates nothing after the first save.
#[derive(Default)]
pub struct StateSlot(Option<Box<dyn Any + Send>>);

impl StateSlot {
    /// An empty slot.
    pub fn new() -> StateSlot {
        StateSlot(None)
    }

    /// Whether a state has been stored.
    pub fn is_empty(&self) -> bool {
        self.0.is_none()
    }

    /// Saves a copy of `state`, reusing the slot's memory when it already holds a
    /// state of the same type.
    pub fn store<S: Clone + Send + 'static>(&mut self, state: &S) {
        match self.0.as_mut().and_then(|b| b.downcast_mut::<S>()) {
            Some(saved) => saved.clone_from(state),
            None => self.0 = Some(Box::new(state.clone())),
        }
    }

    /// The saved state, or an error if the slot is empty or holds another unit's state.
    pub fn load<S: 'static>(&self) -> Result<&S, UnitError> {
        self.0
            .as_ref()
            .and_then(|b| b.downcast_ref::<S>())
            .ok_or_else(|| {
                UnitError::State(
                    "the state slot is empty or was saved by another kind of unit".into(),
                )
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn store_then_load_round_trips_and_rejects_another_type() {
        let mut slot = StateSlot::new();
        assert!(slot.is_empty());
        slot.store(&vec![1.0, 2.0]);
        slot.store(&vec![3.0, 4.0]);
        assert_eq!(slot.load::<Vec<f64>>().unwrap(), &vec![3.0, 4.0]);
        assert!(slot.load::<f64>().is_err());
    }
}
