//! FMU states through the C API, shared by both FMI versions (their functions differ only in
//! name and status type): get, set, free, and the serialized form.
//!
//! A state handle is an opaque token, looked up in the instance's registry (`inst.states`) before
//! it is used: freed, foreign and garbage handles are refused, and never dereferenced.
use super::ffi::{input, out_ref, output};
use super::instance::Instance;
use super::state_machine::{error, mask, FmiResult};
use std::os::raw::c_void;

type Handle = *mut c_void;

/// Takes a copy of the instance's state. `*slot` NULL: a new state. `*slot` a live state of this
/// instance: updated in place. Anything else breaks the standard's precondition; it is never
/// dereferenced nor freed: a new state is written over it and the call warns (`Ok(true)`; some
/// hosts pass an uninitialized slot).
///
/// # Safety
/// A non-NULL `slot` must be writable.
/// `arg` is the handle's name in the version's header (`FMUstate`, `FMUState`), for messages.
pub unsafe fn get(
    inst: &mut Instance,
    slot: *mut Handle,
    func: &str,
    arg: &str,
) -> FmiResult<bool> {
    inst.require(mask::ANY)?;
    let slot = out_ref(slot, arg)?;
    let data = inst.get_fmu_state()?;
    let old = *slot;
    if inst.states.owns(old) {
        inst.states.replace(old, data, &format!("*{arg}"))?;
        return Ok(false);
    }
    let replaced_foreign = !old.is_null();
    if replaced_foreign {
        inst.log.warning_status(&format!(
            "{func}: *{arg} = {old:p} is neither NULL nor a live state of this instance (the \
             standard allows only these); it was not used, a new state was allocated and \
             written over it"
        ));
    }
    *slot = inst.states.add(data)?;
    Ok(replaced_foreign)
}

pub fn set(inst: &mut Instance, handle: Handle, arg: &str) -> FmiResult<bool> {
    inst.require(mask::ANY)?;
    // A copy: the registry lives in the instance that set_fmu_state changes.
    let data = inst.states.get(handle, arg)?.clone();
    inst.set_fmu_state(&data)?;
    Ok(false)
}

/// Frees a state and sets `*slot = NULL`; NULL (either level) is ignored. A handle that is not
/// a live state of this instance (freed already, another instance's, garbage) is refused and
/// left as it is.
///
/// # Safety
/// A non-NULL `slot` must be readable and writable.
pub unsafe fn free(inst: &mut Instance, slot: *mut Handle, arg: &str) -> FmiResult<bool> {
    inst.require(mask::ANY)?;
    if slot.is_null() {
        return Ok(false);
    }
    let slot = out_ref(slot, arg)?;
    if slot.is_null() {
        return Ok(false);
    }
    inst.states.free(*slot, &format!("*{arg}"))?;
    *slot = std::ptr::null_mut();
    Ok(false)
}

/// # Safety
/// A non-NULL `size` must be writable.
pub unsafe fn serialized_size(
    inst: &mut Instance,
    handle: Handle,
    size: *mut usize,
) -> FmiResult<bool> {
    inst.require(mask::ANY)?;
    let bytes = inst.serialize_state(handle)?;
    *out_ref(size, "size")? = bytes.len();
    Ok(false)
}

/// # Safety
/// A non-NULL `buffer` must be writable for `size` bytes.
pub unsafe fn serialize(
    inst: &mut Instance,
    handle: Handle,
    buffer: *mut u8,
    size: usize,
    size_func: &str,
) -> FmiResult<bool> {
    inst.require(mask::ANY)?;
    let bytes = inst.serialize_state(handle)?;
    if size != bytes.len() {
        return error(format!(
            "size = {size} differs from the serialized size {} (ask {size_func})",
            bytes.len()
        ));
    }
    output(buffer, size, "serializedState")?.copy_from_slice(&bytes);
    inst.log
        .event(|| format!("FMU state serialized ({size} bytes)"));
    Ok(false)
}

/// Always allocates a new state and writes its handle to `*slot`, which is an output only: it is
/// never read, and a state it held stays valid (free it separately). On a refusal `*slot` is
/// left as it was.
///
/// # Safety
/// A non-NULL `bytes` must be readable for `size` bytes, a non-NULL `slot` writable.
pub unsafe fn deserialize(
    inst: &mut Instance,
    bytes: *const u8,
    size: usize,
    slot: *mut Handle,
    arg: &str,
) -> FmiResult<bool> {
    inst.require(mask::ANY)?;
    let bytes = input(bytes, size, "serializedState")?;
    let slot = out_ref(slot, arg)?;
    let data = inst.deserialize_state(bytes)?;
    *slot = inst.states.add(data)?;
    inst.log
        .event(|| format!("FMU state deserialized ({size} bytes)"));
    Ok(false)
}
