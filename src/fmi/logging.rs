//! Log categories and the per-instance logger.
//!
//! Rules:
//! - errors (`fmi2Error`, category `logStatusError`) and discarded steps (`fmi2Discard`, category
//!   `logStatusWarning`) are always passed to the host's logger when one was given;
//! - everything else only when debug logging is on for its category (`fmi2Instantiate`'s
//!   `loggingOn`, then `fmi2SetDebugLogging`); `logAll` switches on every message, including a
//!   trace of each FMI call;
//! - the logger is always called as `logger(env, instanceName, status, category, "%s", text)`:
//!   the text is the variadic argument, never the format, so a `%` anywhere is harmless.
use super::types::{fmi2CallbackLogger, fmi2ComponentEnvironment, fmi2Status};
use super::types3::{fmi3LogMessageCallback, fmi3Status};
use std::ffi::{CStr, CString};

/// The log categories of the FMU, `(name, description)`, as declared in modelDescription.xml.
pub use crate::packaging::model_description::LOG_CATEGORIES;

/// One of [`LOG_CATEGORIES`]; the discriminant is the index there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Category {
    Events = 0,
    StatusWarning = 1,
    StatusError = 2,
    All = 3,
}

impl Category {
    fn c_name(self) -> &'static CStr {
        // Kept next to LOG_CATEGORIES; the unit test below checks they agree.
        match self {
            Category::Events => c"logEvents",
            Category::StatusWarning => c"logStatusWarning",
            Category::StatusError => c"logStatusError",
            Category::All => c"logAll",
        }
    }
}

/// The host's logging function: FMI 2.0's (a printf format) or FMI 3.0's (plain text).
#[derive(Clone, Copy)]
pub enum Callback {
    Fmi2(fmi2CallbackLogger),
    Fmi3(fmi3LogMessageCallback),
}

/// Where an instance's messages go.
pub struct Logger {
    callback: Option<Callback>,
    /// Handed back unchanged (even NULL) with every message.
    env: fmi2ComponentEnvironment,
    /// Our own copy of `instanceName`: the host may free its string after `fmi2Instantiate`.
    name: CString,
    enabled: [bool; LOG_CATEGORIES.len()],
}

impl Logger {
    pub fn new(
        callback: Option<Callback>,
        env: fmi2ComponentEnvironment,
        name: &str,
        logging_on: bool,
    ) -> Logger {
        Logger {
            callback,
            env,
            name: to_cstring(name),
            enabled: [logging_on; LOG_CATEGORIES.len()],
        }
    }

    pub fn instance_name(&self) -> &str {
        self.name.to_str().unwrap_or("")
    }

    /// `fmi2SetDebugLogging`: `on` applies to the listed categories, or to all when the list is
    /// empty. An unknown name refuses the whole call (nothing changes).
    pub fn set_debug_logging(&mut self, on: bool, categories: &[&str]) -> Result<(), String> {
        let mut enabled = self.enabled;
        if categories.is_empty() {
            enabled = [on; LOG_CATEGORIES.len()];
        }
        for name in categories {
            let index = LOG_CATEGORIES
                .iter()
                .position(|(n, _)| n == name)
                .ok_or_else(|| {
                    let known: Vec<&str> = LOG_CATEGORIES.iter().map(|(n, _)| *n).collect();
                    format!(
                        "unknown log category \"{name}\" (known: {})",
                        known.join(", ")
                    )
                })?;
            enabled[index] = on;
        }
        self.enabled = enabled;
        Ok(())
    }

    /// Whether a message of this category would reach the host.
    pub fn wants(&self, category: Category) -> bool {
        self.callback.is_some()
            && (category == Category::StatusError
                || self.enabled[category as usize]
                || self.enabled[Category::All as usize])
    }

    /// An error: always logged.
    pub fn error(&self, text: &str) {
        self.emit(fmi2Status::Error, Category::StatusError, text);
    }

    /// A discarded step: always logged (the host must learn why).
    pub fn discard(&self, text: &str) {
        self.send(fmi2Status::Discard, Category::StatusWarning, text);
    }

    pub fn warning(&self, text: &str) {
        self.emit(fmi2Status::Warning, Category::StatusWarning, text);
    }

    /// The reason of a call that returns `fmi2Warning`: always logged (the host must learn why).
    pub fn warning_status(&self, text: &str) {
        self.send(fmi2Status::Warning, Category::StatusWarning, text);
    }

    /// A change of the instance's state; the text is only built when it will be sent.
    pub fn event(&self, text: impl FnOnce() -> String) {
        if self.wants(Category::Events) {
            self.send(fmi2Status::OK, Category::Events, &text());
        }
    }

    /// A trace of an FMI call (`logAll` only).
    pub fn trace(&self, text: impl FnOnce() -> String) {
        if self.wants(Category::All) {
            self.send(fmi2Status::OK, Category::All, &text());
        }
    }

    fn emit(&self, status: fmi2Status, category: Category, text: &str) {
        if self.wants(category) {
            self.send(status, category, text);
        }
    }

    fn send(&self, status: fmi2Status, category: Category, text: &str) {
        let text = to_cstring(text);
        let category = category.c_name().as_ptr();
        // SAFETY: the host promised a valid logger; every pointer is a live NUL-terminated
        // string for the duration of the call, and "%s" consumes exactly one `char*`.
        match self.callback {
            Some(Callback::Fmi2(logger)) => unsafe {
                logger(
                    self.env,
                    self.name.as_ptr(),
                    status,
                    category,
                    c"%s".as_ptr(),
                    text.as_ptr(),
                )
            },
            Some(Callback::Fmi3(logger)) => unsafe {
                logger(self.env, fmi3_status(status), category, text.as_ptr())
            },
            None => {}
        }
    }
}

/// The FMI 3.0 status of a message (FMI 3.0 has no `Pending`, which is never logged).
fn fmi3_status(status: fmi2Status) -> fmi3Status {
    match status {
        fmi2Status::OK | fmi2Status::Pending => fmi3Status::OK,
        fmi2Status::Warning => fmi3Status::Warning,
        fmi2Status::Discard => fmi3Status::Discard,
        fmi2Status::Error => fmi3Status::Error,
        fmi2Status::Fatal => fmi3Status::Fatal,
    }
}

/// A C string of `text` with interior NULs dropped (they would truncate the message).
pub fn to_cstring(text: &str) -> CString {
    CString::new(text.replace('\0', "")).expect("interior NULs were removed")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn category_names_match_the_table() {
        for (i, c) in [
            Category::Events,
            Category::StatusWarning,
            Category::StatusError,
            Category::All,
        ]
        .into_iter()
        .enumerate()
        {
            assert_eq!(c as usize, i);
            assert_eq!(c.c_name().to_str().unwrap(), LOG_CATEGORIES[i].0);
        }
    }

    #[test]
    fn debug_logging_by_category() {
        let mut log = Logger::new(None, std::ptr::null_mut(), "x", false);
        log.set_debug_logging(true, &["logEvents"]).unwrap();
        assert_eq!(log.enabled, [true, false, false, false]);
        assert!(log.set_debug_logging(true, &["logAll", "nope"]).is_err());
        assert_eq!(
            log.enabled,
            [true, false, false, false],
            "a refused call changes nothing"
        );
        log.set_debug_logging(false, &[]).unwrap();
        assert_eq!(log.enabled, [false; 4]);
    }
}
