//! What the C shims of both FMI versions share: running a call on an instance behind its
//! opaque handle (pointer check, `catch_unwind`, logging a refusal) and turning C pointers into
//! slices. Version-free: [`Outcome`] becomes `fmi2Status` or `fmi3Status` in the shim.
use super::instance::Instance;
use super::state_machine::{error, Failure, FmiResult};
use std::ffi::CStr;
use std::os::raw::{c_char, c_void};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// How a call ended (the status values both FMI versions have).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    Ok,
    Warning,
    Discard,
    Error,
}

fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic payload".to_string())
}

/// Runs `f` on the instance behind `c`, logging failures as `"<func>: why"`. A bad instance
/// pointer is an error without a message (there is no logger). `f` answers `true` for a call
/// that succeeded with a warning (its reason already logged).
pub(crate) fn call(
    c: *mut c_void,
    func: &'static str,
    f: impl FnOnce(&mut Instance) -> FmiResult<bool>,
) -> Outcome {
    // SAFETY: best-effort check of the host's pointer (see Instance::from_raw).
    let Some(inst) = (unsafe { Instance::from_raw(c) }) else {
        return Outcome::Error;
    };
    let ptr: *mut Instance = inst;
    // SAFETY: `ptr` is the live instance; the closure holds the only reference while it runs.
    match catch_unwind(AssertUnwindSafe(|| f(unsafe { &mut *ptr }))) {
        Ok(Ok(false)) => Outcome::Ok,
        Ok(Ok(true)) => Outcome::Warning,
        Ok(Err(failure)) => {
            // SAFETY: as above; the closure's reference is gone.
            let inst = unsafe { &*ptr };
            match failure {
                Failure::Error(why) => {
                    inst.log.error(&format!("{func}: {why}"));
                    Outcome::Error
                }
                Failure::Discard(why) => {
                    inst.log.discard(&format!("{func}: {why}"));
                    Outcome::Discard
                }
            }
        }
        Err(payload) => {
            // SAFETY: as above; the panic unwound out of the closure.
            let inst = unsafe { &mut *ptr };
            inst.poison();
            inst.log.error(&format!(
                "{func}: internal error (Rust panic: {}); the instance is now in the error state",
                panic_text(payload.as_ref())
            ));
            Outcome::Error
        }
    }
}

/// A C input array as a slice (`n == 0` allows NULL).
///
/// # Safety
/// A non-NULL `p` must be readable for `n` elements.
pub unsafe fn input<'a, T>(p: *const T, n: usize, what: &str) -> FmiResult<&'a [T]> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return error(format!("{what} is NULL but its length is {n}"));
    }
    if !p.is_aligned() || n > isize::MAX as usize / std::mem::size_of::<T>().max(1) {
        return error(format!(
            "{what}: misaligned pointer or impossible length {n}"
        ));
    }
    Ok(std::slice::from_raw_parts(p, n))
}

/// A C output array as a slice (`n == 0` allows NULL).
///
/// # Safety
/// A non-NULL `p` must be writable for `n` elements.
pub unsafe fn output<'a, T>(p: *mut T, n: usize, what: &str) -> FmiResult<&'a mut [T]> {
    if n == 0 {
        return Ok(&mut []);
    }
    input(p as *const T, n, what)?;
    Ok(std::slice::from_raw_parts_mut(p, n))
}

/// A single C output value.
///
/// # Safety
/// A non-NULL `p` must be writable.
pub unsafe fn out_ref<'a, T>(p: *mut T, what: &str) -> FmiResult<&'a mut T> {
    Ok(&mut output(p, 1, what)?[0])
}

/// A C string as UTF-8 (lossy); `None` for NULL.
///
/// # Safety
/// A non-NULL `p` must be a NUL-terminated string.
pub unsafe fn string(p: *const c_char) -> Option<String> {
    (!p.is_null()).then(|| CStr::from_ptr(p).to_string_lossy().into_owned())
}

/// A C array of C strings (`fmi*SetDebugLogging`'s categories).
///
/// # Safety
/// As [`input`], and each non-NULL element as [`string`].
pub unsafe fn strings(p: *const *const c_char, n: usize, what: &str) -> FmiResult<Vec<String>> {
    let mut names = Vec::with_capacity(n);
    for (i, &s) in input(p, n, what)?.iter().enumerate() {
        let name = what.trim_end_matches("[]");
        names.push(string(s).ok_or_else(|| Failure::Error(format!("{name}[{i}] is NULL")))?);
    }
    Ok(names)
}
