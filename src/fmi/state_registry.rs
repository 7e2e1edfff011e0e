//! The FMU states one instance has handed out (`fmi2GetFMUstate`, `fmi2DeSerializeFMUstate`).
//!
//! A handle is the address of a state this registry owns. Every handle a host passes in is
//! looked up here by its value before anything is read: a handle that was freed, belongs to
//! another instance, or was never given out is refused without touching the memory it points to
//! (it may be unmapped). The registry owns its states, so they go with the instance
//! (`fmi2FreeInstance` frees the ones the host did not).
//!
//! Freed slots are kept allocated (their data dropped) for the next [`QUARANTINE`] frees, so that
//! the allocator cannot give a freed address straight to the next state: a stale handle stays
//! detectable for that long. After that an address may come back; a stale handle then names a
//! live state of this same instance, which is memory safe but cannot be told apart.
use super::fmu_state::StateData;
use super::instance::{error, FmiResult};
use super::types::fmi2FMUstate;
use std::collections::{HashMap, VecDeque};

/// Freed slots kept allocated before their address may be reused.
pub const QUARANTINE: usize = 64;

type Slot = Box<Option<StateData>>;

#[derive(Default)]
pub struct StateRegistry {
    live: HashMap<usize, Slot>,
    freed: VecDeque<Slot>,
}

/// `0x...` for messages.
fn show(h: fmi2FMUstate) -> String {
    format!("{h:p}")
}

impl StateRegistry {
    /// Number of states given out and not freed.
    pub fn len(&self) -> usize {
        self.live.len()
    }

    pub fn is_empty(&self) -> bool {
        self.live.is_empty()
    }

    /// Whether `h` is a live state of this registry (NULL is not).
    pub fn owns(&self, h: fmi2FMUstate) -> bool {
        self.live.contains_key(&(h as usize))
    }

    /// Stores `data` and returns its new handle.
    pub fn add(&mut self, data: StateData) -> fmi2FMUstate {
        let slot: Slot = Box::new(Some(data));
        let h = &*slot as *const Option<StateData> as fmi2FMUstate;
        self.live.insert(h as usize, slot);
        h
    }

    fn refuse<T>(&self, h: fmi2FMUstate, arg: &str) -> FmiResult<T> {
        if h.is_null() {
            return error(format!(
                "{arg} is NULL: a state returned by fmi2GetFMUstate or fmi2DeSerializeFMUstate \
                 of this instance is required"
            ));
        }
        error(format!(
            "{arg} = {} is not a live FMU state of this instance (already freed, another \
             instance's, or never returned by its fmi2GetFMUstate / fmi2DeSerializeFMUstate); \
             it was not used",
            show(h)
        ))
    }

    /// The state behind `h`, or an error naming `arg` when `h` is not one of ours.
    pub fn get(&self, h: fmi2FMUstate, arg: &str) -> FmiResult<&StateData> {
        match self
            .live
            .get(&(h as usize))
            .and_then(|s| s.as_ref().as_ref())
        {
            Some(data) => Ok(data),
            None => self.refuse(h, arg),
        }
    }

    /// Replaces the data of the live state `h` (fmi2GetFMUstate updating a state in place).
    pub fn replace(&mut self, h: fmi2FMUstate, data: StateData, arg: &str) -> FmiResult {
        match self.live.get_mut(&(h as usize)) {
            Some(slot) => {
                **slot = Some(data);
                Ok(())
            }
            None => self.refuse(h, arg),
        }
    }

    /// Frees the live state `h`.
    pub fn free(&mut self, h: fmi2FMUstate, arg: &str) -> FmiResult {
        let Some(mut slot) = self.live.remove(&(h as usize)) else {
            return self.refuse(h, arg);
        };
        *slot = None; // the snapshot's vectors go now; the small slot stays in quarantine
        self.freed.push_back(slot);
        if self.freed.len() > QUARANTINE {
            self.freed.pop_front();
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fmi::instance::{Experiment, FmiState};
    use crate::scene::ParamValues;

    fn data() -> StateData {
        StateData {
            scene: "Test".to_string(),
            fmi_state: FmiState::Instantiated,
            experiment: Experiment::default(),
            params: ParamValues(vec![1.0; 10]),
            inputs: Vec::new(),
            snapshot: None,
        }
    }

    #[test]
    fn handles_are_checked_by_value_and_freed_ones_are_not_reused_at_once() {
        let mut r = StateRegistry::default();
        let a = r.add(data());
        assert!(r.owns(a) && r.get(a, "FMUstate").is_ok());
        r.free(a, "FMUstate").unwrap();
        assert!(!r.owns(a));
        assert!(r.free(a, "FMUstate").is_err(), "double free");
        assert!(r.get(a, "FMUstate").is_err(), "use after free");
        // The quarantine keeps `a`'s address out of the next QUARANTINE allocations.
        let fresh: Vec<_> = (0..QUARANTINE).map(|_| r.add(data())).collect();
        assert!(fresh.iter().all(|&h| h != a));
        assert_eq!(r.len(), QUARANTINE);
        let garbage = 0x10 as fmi2FMUstate;
        assert!(r.get(garbage, "FMUstate").is_err());
        assert!(r.get(std::ptr::null_mut(), "FMUstate").is_err());
        assert!(r.replace(garbage, data(), "FMUstate").is_err());
    }
}
