//! The FMU states one instance has handed out (`fmi2GetFMUstate`, `fmi2DeSerializeFMUstate`).
//!
//! A handle is an opaque token, not an address: a number drawn from one process-wide counter
//! (so no two states of any instance ever get the same token, and a token is never given out
//! again after its state is freed), made into a pointer value that no allocation can have. The
//! registry maps tokens to the states it owns. Every handle a host passes in is looked up here
//! by its value, and nothing else is done with it: a handle that was freed (however many states
//! came and went since), freed twice, belongs to another instance, or was never given out is
//! refused, and no memory it might point to is ever touched. The registry owns its states, so
//! they go with the instance (`fmi2FreeInstance` frees the ones the host did not).
use super::state_data::StateData;
use super::state_machine::{error, FmiResult};
use super::types::fmi2FMUstate;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};

/// The serial number of the next token (process-wide; 0 is never used: a token is non-null).
static NEXT: AtomicU64 = AtomicU64::new(1);

/// Tokens are `TAG | serial`, serial < `SERIALS`. On 64-bit targets TAG sets bits above bit 47
/// (bit 63 clear), so a token is not a canonical user or kernel address on x86-64 or aarch64:
/// no pointer a host holds (from malloc, the stack, a mapping) has a token's value.
#[cfg(target_pointer_width = "64")]
const TAG: usize = 0x4745_0000_0000_0000;
#[cfg(target_pointer_width = "64")]
const SERIALS: u64 = 1 << 48;
#[cfg(not(target_pointer_width = "64"))]
const TAG: usize = 0;
#[cfg(not(target_pointer_width = "64"))]
const SERIALS: u64 = usize::MAX as u64;

/// A fresh token, or `None` once the process has used up every serial (2^48 on 64-bit targets:
/// at a million states a second, about nine years). Tokens are never reused, not even then.
fn new_token() -> Option<usize> {
    let serial = NEXT.fetch_add(1, Ordering::Relaxed);
    (serial < SERIALS).then_some(TAG | serial as usize)
}

/// The handle of a token: an integer made into a pointer, never dereferenced (it carries no
/// provenance; hosts treat `fmi2FMUstate` as opaque, and so does the FMU).
fn handle(token: usize) -> fmi2FMUstate {
    token as fmi2FMUstate
}

#[derive(Default)]
pub struct StateRegistry {
    live: HashMap<usize, StateData>,
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

    /// Stores `data` under a new token and returns its handle.
    pub fn add(&mut self, data: StateData) -> FmiResult<fmi2FMUstate> {
        let Some(token) = new_token() else {
            return error(format!(
                "no FMU state handle left: this process has given out all {SERIALS} (handles \
                 are never reused)"
            ));
        };
        self.live.insert(token, data);
        Ok(handle(token))
    }

    fn refuse<T>(&self, h: fmi2FMUstate, arg: &str) -> FmiResult<T> {
        if h.is_null() {
            return error(format!(
                "{arg} is NULL: a state returned by fmi2GetFMUstate or fmi2DeSerializeFMUstate \
                 of this instance is required"
            ));
        }
        error(format!(
            "{arg} = {h:p} is not a live FMU state of this instance (already freed, another \
             instance's, or never returned by its fmi2GetFMUstate / fmi2DeSerializeFMUstate); \
             it was not used"
        ))
    }

    /// The state behind `h`, or an error naming `arg` when `h` is not one of ours.
    pub fn get(&self, h: fmi2FMUstate, arg: &str) -> FmiResult<&StateData> {
        match self.live.get(&(h as usize)) {
            Some(data) => Ok(data),
            None => self.refuse(h, arg),
        }
    }

    /// Replaces the data of the live state `h` (fmi2GetFMUstate updating a state in place: the
    /// handle stays the same).
    pub fn replace(&mut self, h: fmi2FMUstate, data: StateData, arg: &str) -> FmiResult {
        match self.live.get_mut(&(h as usize)) {
            Some(slot) => {
                *slot = data;
                Ok(())
            }
            None => self.refuse(h, arg),
        }
    }

    /// Frees the live state `h`; its token is dead for good.
    pub fn free(&mut self, h: fmi2FMUstate, arg: &str) -> FmiResult {
        match self.live.remove(&(h as usize)) {
            Some(_) => Ok(()),
            None => self.refuse(h, arg),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fmi::experiment::Experiment;
    use crate::fmi::state_machine::FmiState;
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
    fn tokens_are_checked_by_value_and_never_come_back() {
        let (mut r, mut other) = (StateRegistry::default(), StateRegistry::default());
        let a = r.add(data()).unwrap();
        assert!(!a.is_null() && r.owns(a) && r.get(a, "FMUstate").is_ok());
        r.free(a, "FMUstate").unwrap();
        assert!(!r.owns(a));
        assert!(r.free(a, "FMUstate").is_err(), "double free");
        assert!(r.get(a, "FMUstate").is_err(), "use after free");
        let mut seen = std::collections::HashSet::from([a as usize]);
        for _ in 0..1000 {
            let h = r.add(data()).unwrap();
            let theirs = other.add(data()).unwrap();
            assert!(seen.insert(h as usize) && seen.insert(theirs as usize));
            assert!(!other.owns(h) && !r.owns(theirs), "tokens are process-wide");
            r.free(h, "FMUstate").unwrap();
        }
        assert!(r.is_empty() && other.len() == 1000);
        assert!(r.get(a, "FMUstate").is_err());
        let garbage = 0x10 as fmi2FMUstate;
        assert!(r.get(garbage, "FMUstate").is_err());
        assert!(r.get(std::ptr::null_mut(), "FMUstate").is_err());
        assert!(r.replace(garbage, data(), "FMUstate").is_err());
    }
}
