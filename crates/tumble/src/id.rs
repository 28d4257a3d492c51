//! Typed ids with generations, and the slot pool that hands them out.
//!
//! An id is an index into a pool plus the generation of the slot when the id was made. Removing an
//! object bumps its slot's generation, so an old id held by the user no longer matches: it is an
//! error ("stale id"), never a silent reference to whatever reused the slot.

use std::fmt;

macro_rules! typed_id {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize)]
        pub struct $name {
            index: u32,
            generation: u32,
        }

        impl $name {
            /// The slot index (dense, reused after removal).
            pub fn index(self) -> usize {
                self.index as usize
            }
            /// The slot's generation when this id was made.
            pub fn generation(self) -> u32 {
                self.generation
            }
            /// Builds an id from its parts (for snapshots and bindings; a wrong pair is simply stale).
            pub fn from_parts(index: u32, generation: u32) -> Self {
                Self { index, generation }
            }
        }

        impl fmt::Debug for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "{}({}v{})", stringify!($name), self.index, self.generation)
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                fmt::Debug::fmt(self, f)
            }
        }

        impl From<$name> for RawId {
            fn from(id: $name) -> RawId {
                RawId { index: id.index, generation: id.generation }
            }
        }

        impl From<RawId> for $name {
            fn from(id: RawId) -> $name {
                $name { index: id.index, generation: id.generation }
            }
        }
    };
}

typed_id!(
    /// Names a body in a `World`.
    BodyId
);

typed_id!(
    /// Names a joint in a `World`.
    JointId
);

/// An untyped id, used by the pool; the typed ids convert to and from it.
#[derive(Clone, Copy, PartialEq, Eq, Debug, serde::Serialize, serde::Deserialize)]
pub struct RawId {
    index: u32,
    generation: u32,
}

impl RawId {
    /// The slot index.
    pub fn index(self) -> usize {
        self.index as usize
    }
}

/// One place of a [`SlotPool`]: its object, if live, and how often the place was freed.
#[derive(Clone, serde::Serialize, serde::Deserialize)]
pub(crate) struct Slot<T> {
    generation: u32,
    value: Option<T>,
}

impl<T> Slot<T> {
    /// The live object here, if any.
    pub(crate) fn value(&self) -> Option<&T> {
        self.value.as_ref()
    }

    /// The live object here, if any.
    pub(crate) fn value_mut(&mut self) -> Option<&mut T> {
        self.value.as_mut()
    }
}

/// A pool of slots: insert gives an id, remove frees the slot and bumps its generation.
/// Iteration is in slot-index order, which keeps every loop over it deterministic.
#[derive(Clone, serde::Serialize, serde::Deserialize)]
pub struct SlotPool<T> {
    slots: Vec<Slot<T>>,
    free: Vec<u32>,
    len: usize,
}

impl<T> Default for SlotPool<T> {
    fn default() -> Self {
        Self { slots: Vec::new(), free: Vec::new(), len: 0 }
    }
}

impl<T> SlotPool<T> {
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of live objects.
    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// One past the highest slot index ever used (live or free).
    pub fn capacity_index(&self) -> usize {
        self.slots.len()
    }

    pub fn insert(&mut self, value: T) -> RawId {
        self.len += 1;
        // Reuse the most recently freed slot: deterministic, and keeps the arrays dense.
        if let Some(index) = self.free.pop() {
            let slot = &mut self.slots[index as usize];
            slot.value = Some(value);
            RawId { index, generation: slot.generation }
        } else {
            let index = u32::try_from(self.slots.len()).expect("more than 2^32 objects in one pool");
            self.slots.push(Slot { generation: 0, value: Some(value) });
            RawId { index, generation: 0 }
        }
    }

    pub fn remove(&mut self, id: RawId) -> Option<T> {
        let slot = self.slots.get_mut(id.index as usize)?;
        if slot.generation != id.generation || slot.value.is_none() {
            return None;
        }
        slot.generation = slot.generation.wrapping_add(1);
        self.free.push(id.index);
        self.len -= 1;
        slot.value.take()
    }

    pub fn get(&self, id: RawId) -> Option<&T> {
        let slot = self.slots.get(id.index as usize)?;
        if slot.generation != id.generation {
            return None;
        }
        slot.value.as_ref()
    }

    pub fn get_mut(&mut self, id: RawId) -> Option<&mut T> {
        let slot = self.slots.get_mut(id.index as usize)?;
        if slot.generation != id.generation {
            return None;
        }
        slot.value.as_mut()
    }

    /// The id of the live object in slot `index`.
    pub fn id_of_slot(&self, index: usize) -> Option<RawId> {
        let slot = self.slots.get(index)?;
        slot.value.as_ref().map(|_| RawId { index: index as u32, generation: slot.generation })
    }

    /// The live object in slot `index`, whatever its generation.
    pub fn iter_slot(&self, index: usize) -> Option<&T> {
        self.slots.get(index).and_then(|s| s.value.as_ref())
    }

    /// Live objects with their ids, in slot order.
    pub fn iter(&self) -> impl Iterator<Item = (RawId, &T)> {
        self.slots.iter().enumerate().filter_map(|(i, s)| {
            s.value.as_ref().map(|v| (RawId { index: i as u32, generation: s.generation }, v))
        })
    }

    /// Every slot, live or free, in slot order (slot `i` at index `i`).
    #[cfg(test)]
    pub(crate) fn slots(&self) -> &[Slot<T>] {
        &self.slots
    }

    /// Every slot, live or free, in slot order (slot `i` at index `i`): to split between threads.
    pub(crate) fn slots_mut(&mut self) -> &mut [Slot<T>] {
        &mut self.slots
    }

    /// Live objects with their ids, in slot order, mutably.
    pub fn iter_mut(&mut self) -> impl Iterator<Item = (RawId, &mut T)> {
        self.slots.iter_mut().enumerate().filter_map(|(i, s)| {
            let generation = s.generation;
            s.value.as_mut().map(|v| (RawId { index: i as u32, generation }, v))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stale_ids_do_not_resolve() {
        let mut pool = SlotPool::new();
        let a = pool.insert("a");
        assert_eq!(pool.remove(a), Some("a"));
        let b = pool.insert("b");
        assert_eq!(a.index, b.index, "slot is reused");
        assert_eq!(pool.get(a), None, "the old id is stale");
        assert_eq!(pool.get(b), Some(&"b"));
        assert_eq!(pool.remove(a), None);
        assert_eq!(pool.len(), 1);
    }
}
