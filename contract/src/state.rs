//! Storage for a unit's saved state, used by the master to roll units back and by
//! the FMI layer to serialise a unit's state into bytes.

use crate::UnitError;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::any::Any;
use std::borrow::Cow;

/// A saved state of some unit's state type, able to write itself as bytes.
trait SavedState: Send {
    fn as_any(&self) -> &dyn Any;
    fn as_any_mut(&mut self) -> &mut dyn Any;
    fn to_bytes(&self) -> Result<Vec<u8>, UnitError>;
}

impl<S: Any + Send + Serialize> SavedState for S {
    fn as_any(&self) -> &dyn Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }

    fn to_bytes(&self) -> Result<Vec<u8>, UnitError> {
        postcard::to_stdvec(self).map_err(|e| UnitError::State(format!("serialising: {e}")))
    }
}

#[derive(Default)]
enum Saved {
    #[default]
    Empty,
    /// Saved by the unit itself (the master's rollback path).
    Typed(Box<dyn SavedState>),
    /// Read from bytes (an FMU state deserialised by the FMI layer); the unit
    /// decodes it on restore.
    Bytes(Vec<u8>),
    /// Saved by a unit that wraps another: its own state and the inner unit's
    /// slot ([`StateSlot::store_nested`]).
    Nested(Box<dyn SavedState>, Box<StateSlot>),
}

/// The inner unit's slot of a nested state ([`StateSlot::load_nested`]):
/// borrowed when the outer unit saved it, decoded when it came from bytes.
pub enum NestedSlot<'a> {
    /// The outer unit's own slot of it, as saved.
    Borrowed(&'a StateSlot),
    /// Decoded from the outer state's bytes (an FMU state read back).
    Owned(StateSlot),
}

impl std::ops::Deref for NestedSlot<'_> {
    type Target = StateSlot;

    fn deref(&self) -> &StateSlot {
        match self {
            NestedSlot::Borrowed(slot) => slot,
            NestedSlot::Owned(slot) => slot,
        }
    }
}

/// An opaque slot that holds one saved state of one unit.
///
/// The master keeps one slot per unit and reuses it at every synchronisation step;
/// [`StateSlot::store`] uses `clone_from`, so a state type whose `Clone` implements
/// `clone_from` field by field allocates nothing after the first save. A slot
/// converts to and from bytes (postcard, exact f64 bits) for FMU state
/// serialisation.
#[derive(Default)]
pub struct StateSlot(Saved);

impl StateSlot {
    /// An empty slot.
    pub fn new() -> StateSlot {
        StateSlot(Saved::Empty)
    }

    /// A slot holding a state serialised by [`StateSlot::to_bytes`]; the unit that
    /// restores from it decodes and checks it.
    pub fn from_bytes(bytes: Vec<u8>) -> StateSlot {
        StateSlot(Saved::Bytes(bytes))
    }

    /// Whether a state has been stored.
    pub fn is_empty(&self) -> bool {
        matches!(self.0, Saved::Empty)
    }

    /// Saves a copy of `state`, reusing the slot's memory when it already holds a
    /// state of the same type.
    pub fn store<S: Clone + Send + Serialize + 'static>(&mut self, state: &S) {
        if let Saved::Typed(saved) = &mut self.0
            && let Some(saved) = saved.as_any_mut().downcast_mut::<S>()
        {
            saved.clone_from(state);
            return;
        }
        self.0 = Saved::Typed(Box::new(state.clone()));
    }

    /// Saves a copy of `own`, the state of a unit that wraps another, and
    /// returns the slot the inner unit saves into; reuses the slot's memory
    /// when it already holds such a pair.
    pub fn store_nested<S: Clone + Send + Serialize + 'static>(
        &mut self,
        own: &S,
    ) -> Result<&mut StateSlot, UnitError> {
        let reusable = matches!(&self.0, Saved::Nested(saved, _) if saved.as_any().is::<S>());
        if !reusable {
            self.0 = Saved::Nested(Box::new(own.clone()), Box::new(StateSlot::new()));
        }
        match &mut self.0 {
            Saved::Nested(saved, inner) => {
                if let Some(saved) = saved.as_any_mut().downcast_mut::<S>() {
                    saved.clone_from(own);
                }
                Ok(inner)
            }
            _ => Err(UnitError::State("the slot holds no nested state".into())),
        }
    }

    /// The state saved by [`StateSlot::store_nested`]: the outer unit's own
    /// and the inner unit's slot; an error when the slot holds anything else.
    pub fn load_nested<S: Clone + DeserializeOwned + 'static>(
        &self,
    ) -> Result<(Cow<'_, S>, NestedSlot<'_>), UnitError> {
        let mismatch = || {
            UnitError::State(
                "the state slot is empty or was saved by another kind of unit (expected a wrapping unit's)"
                    .into(),
            )
        };
        match &self.0 {
            Saved::Nested(saved, inner) => {
                let own = saved.as_any().downcast_ref::<S>().ok_or_else(mismatch)?;
                Ok((Cow::Borrowed(own), NestedSlot::Borrowed(inner)))
            }
            Saved::Bytes(bytes) => {
                let (own, inner): (Vec<u8>, Vec<u8>) =
                    postcard::from_bytes(bytes).map_err(|e| {
                        UnitError::State(format!(
                            "the serialised state does not decode as a wrapping unit's state ({e})"
                        ))
                    })?;
                let own = postcard::from_bytes::<S>(&own).map_err(|e| {
                    UnitError::State(format!(
                        "the serialised state does not decode as this unit's state ({e})"
                    ))
                })?;
                Ok((
                    Cow::Owned(own),
                    NestedSlot::Owned(StateSlot::from_bytes(inner)),
                ))
            }
            _ => Err(mismatch()),
        }
    }

    /// The saved state for in-place update, when the slot holds one of type `S`
    /// saved by a unit (not read from bytes).
    pub fn get_mut<S: 'static>(&mut self) -> Option<&mut S> {
        match &mut self.0 {
            Saved::Typed(saved) => saved.as_any_mut().downcast_mut::<S>(),
            _ => None,
        }
    }

    /// The saved state, or an error if the slot is empty or holds another unit's
    /// state. Borrowed when the unit saved it, decoded when it came from bytes.
    pub fn load<S: Clone + DeserializeOwned + 'static>(&self) -> Result<Cow<'_, S>, UnitError> {
        let mismatch = || {
            UnitError::State("the state slot is empty or was saved by another kind of unit".into())
        };
        match &self.0 {
            Saved::Empty | Saved::Nested(..) => Err(mismatch()),
            Saved::Typed(saved) => saved
                .as_any()
                .downcast_ref::<S>()
                .map(Cow::Borrowed)
                .ok_or_else(mismatch),
            Saved::Bytes(bytes) => match postcard::from_bytes::<S>(bytes) {
                Ok(state) => Ok(Cow::Owned(state)),
                Err(e) => Err(UnitError::State(format!(
                    "the serialised state does not decode as this unit's state ({e})"
                ))),
            },
        }
    }

    /// The saved state as bytes (postcard encoding of the unit's state type).
    pub fn to_bytes(&self) -> Result<Vec<u8>, UnitError> {
        match &self.0 {
            Saved::Empty => Err(UnitError::State("no state saved".into())),
            Saved::Typed(saved) => saved.to_bytes(),
            Saved::Bytes(bytes) => Ok(bytes.clone()),
            Saved::Nested(saved, inner) => {
                postcard::to_stdvec(&(saved.to_bytes()?, inner.to_bytes()?))
                    .map_err(|e| UnitError::State(format!("serialising: {e}")))
            }
        }
    }
}

/// Defines a unit's state struct with a `Clone` whose `clone_from` copies field by
/// field (`Vec`s reuse their memory), so rollback through [`StateSlot::store`] and
/// `clone_from` allocates nothing and no field list is written by hand.
///
/// Every field's own `clone_from` must reuse memory: `Vec`, arrays, numbers,
/// `Option` of such, and nested `state_struct!`s do; nalgebra's `DVector` does not
/// (wrap it in a type with its own `clone_from`, as `NewmarkState` does).
#[macro_export]
macro_rules! state_struct {
    (
        $(#[$meta:meta])*
        $vis:vis struct $name:ident {
            $($(#[$field_meta:meta])* $field_vis:vis $field:ident : $ty:ty),* $(,)?
        }
    ) => {
        $(#[$meta])*
        $vis struct $name {
            $($(#[$field_meta])* $field_vis $field: $ty),*
        }

        impl Clone for $name {
            fn clone(&self) -> Self {
                $name { $($field: Clone::clone(&self.$field)),* }
            }

            fn clone_from(&mut self, source: &Self) {
                $(Clone::clone_from(&mut self.$field, &source.$field);)*
            }
        }
    };
}

/// A [`Unit`](crate::Unit)'s `save_state` and `restore_state` when its whole
/// rollback state is one field of a [`state_struct!`](crate::state_struct)
/// type: stored whole, restored by `clone_from` (no allocation). The optional
/// block runs after a restore with the unit bound to the name given, for what
/// a rollback must also reset (a stale step Jacobian, a cached start).
#[macro_export]
macro_rules! state_in_field {
    ($field:ident : $ty:ty) => {
        $crate::state_in_field!($field: $ty, |_unit| {});
    };
    ($field:ident : $ty:ty, |$unit:ident| $after:block) => {
        fn save_state(&self, slot: &mut $crate::StateSlot) -> Result<(), $crate::UnitError> {
            slot.store(&self.$field);
            Ok(())
        }

        fn restore_state(&mut self, slot: &$crate::StateSlot) -> Result<(), $crate::UnitError> {
            self.$field.clone_from(&*slot.load::<$ty>()?);
            let $unit = &mut *self;
            $after
            Ok(())
        }
    };
}

/// A nalgebra vector in a unit's state whose `clone_from` copies in place when the
/// lengths agree (nalgebra's own `clone_from` allocates), for [`state_struct!`](crate::state_struct).
#[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(transparent)]
pub struct StateVector(pub nalgebra::DVector<f64>);

impl Clone for StateVector {
    fn clone(&self) -> Self {
        StateVector(self.0.clone())
    }

    fn clone_from(&mut self, source: &Self) {
        if self.0.len() == source.0.len() {
            self.0.copy_from(&source.0);
        } else {
            self.0 = source.0.clone();
        }
    }
}

impl std::ops::Deref for StateVector {
    type Target = nalgebra::DVector<f64>;

    fn deref(&self) -> &Self::Target {
        &self.0
    }
}

impl std::ops::DerefMut for StateVector {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.0
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
        assert_eq!(*slot.load::<Vec<f64>>().unwrap(), vec![3.0, 4.0]);
        assert!(slot.load::<f64>().is_err());
    }

    #[test]
    fn bytes_round_trip_exactly_and_garbage_is_an_error() {
        let mut slot = StateSlot::new();
        let state = (vec![0.1_f64, f64::NEG_INFINITY, 1e-300], 7_u64);
        slot.store(&state);
        let copy = StateSlot::from_bytes(slot.to_bytes().unwrap());
        let back = copy.load::<(Vec<f64>, u64)>().unwrap();
        assert_eq!(back.0[0].to_bits(), 0.1_f64.to_bits());
        assert_eq!(*back, state);
        let garbage = StateSlot::from_bytes(vec![0xff; 3]);
        assert!(garbage.load::<(Vec<f64>, u64)>().is_err());
        assert!(StateSlot::new().to_bytes().is_err());
    }

    #[test]
    fn a_nested_state_round_trips_in_memory_and_through_bytes() {
        let mut slot = StateSlot::new();
        slot.store_nested(&[1.5_f64, -2.0])
            .unwrap()
            .store(&vec![3.0_f64]);
        slot.store_nested(&[0.25_f64, 4.0])
            .unwrap()
            .store(&vec![5.0_f64]);
        let (own, inner) = slot.load_nested::<[f64; 2]>().unwrap();
        assert_eq!(*own, [0.25, 4.0]);
        assert_eq!(*inner.load::<Vec<f64>>().unwrap(), vec![5.0]);
        let copy = StateSlot::from_bytes(slot.to_bytes().unwrap());
        let (own, inner) = copy.load_nested::<[f64; 2]>().unwrap();
        assert_eq!(*own, [0.25, 4.0]);
        assert_eq!(*inner.load::<Vec<f64>>().unwrap(), vec![5.0]);
        assert!(slot.load::<[f64; 2]>().is_err());
        assert!(slot.load_nested::<u64>().is_err());
        assert!(StateSlot::new().load_nested::<[f64; 2]>().is_err());
    }
}
