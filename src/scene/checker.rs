//! The tools of the scene checker: a [`Checker`] makes the errors, each naming the file and the
//! key, and checks single values (names, stations, choices, value slots); the helpers below
//! spell the keys of array-of-tables entries for those messages.
use super::params::Param;
use super::{SceneError, Slot};

/// Checks of one scene file: `file` names it in every error.
pub(super) struct Checker<'a> {
    pub(super) file: &'a str,
}

impl Checker<'_> {
    pub(super) fn err<T>(
        &self,
        key: impl Into<String>,
        message: impl Into<String>,
    ) -> Result<T, SceneError> {
        Err(SceneError {
            file: self.file.to_string(),
            key: key.into(),
            message: message.into(),
        })
    }

    /// The error itself (for `ok_or_else`).
    pub(super) fn error(&self, key: impl Into<String>, message: impl Into<String>) -> SceneError {
        SceneError {
            file: self.file.to_string(),
            key: key.into(),
            message: message.into(),
        }
    }

    pub(super) fn required<T>(
        &self,
        value: Option<T>,
        key: &str,
        what: &str,
    ) -> Result<T, SceneError> {
        match value {
            Some(v) => Ok(v),
            None => self.err(key, format!("missing: {what}")),
        }
    }

    /// A name usable as an FMI variable or model identifier: a C identifier.
    pub(super) fn identifier(
        &self,
        name: Option<&String>,
        key: &str,
    ) -> Result<String, SceneError> {
        let name = self.required(name, key, "a name (a C identifier: letters, digits, _)")?;
        let mut chars = name.chars();
        let ok = chars
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && chars.all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !ok {
            return self.err(
                key,
                format!("`{name}` is not a C identifier (letters, digits and _, not starting with a digit)"),
            );
        }
        Ok(name.clone())
    }

    pub(super) fn station(&self, at: Option<f64>, key: &str) -> Result<f64, SceneError> {
        let at = self.required(at, key, "a station: a fraction of the arc length in [0, 1]")?;
        if !(0.0..=1.0).contains(&at) {
            return self.err(
                key,
                format!("{at} is out of range: a station must be in [0, 1]"),
            );
        }
        Ok(at)
    }

    pub(super) fn one_of(
        &self,
        value: &str,
        allowed: &[&str],
        key: &str,
    ) -> Result<usize, SceneError> {
        match allowed.iter().position(|a| *a == value) {
            Some(i) => Ok(i),
            None => self.err(
                key,
                format!(
                    "`{value}` is not allowed: must be one of {}",
                    quoted(allowed)
                ),
            ),
        }
    }

    /// A value slot: a number, a parameter name, or `-name`.
    pub(super) fn slot(
        &self,
        value: &toml::Value,
        params: &[Param],
        key: &str,
    ) -> Result<Slot, SceneError> {
        match value {
            toml::Value::Float(x) if x.is_finite() => Ok(Slot::Number(*x)),
            toml::Value::Integer(i) => Ok(Slot::Number(*i as f64)),
            toml::Value::String(s) => {
                let (sign, name) = match s.strip_prefix('-') {
                    Some(rest) => (-1.0, rest),
                    None => (1.0, s.as_str()),
                };
                match params.iter().position(|p| p.name == name) {
                    Some(index) => Ok(Slot::Param { index, sign }),
                    None => {
                        let names: Vec<&str> = params.iter().map(|p| p.name.as_str()).collect();
                        self.err(
                            key,
                            format!(
                                "`{name}` is not a declared parameter (declare it with [[parameter]]; \
                                 parameters: {})",
                                names.join(", ")
                            ),
                        )
                    }
                }
            }
            other => self.err(
                key,
                format!("{other} is not a value: write a number, a parameter name, or -name"),
            ),
        }
    }
}

pub(super) fn quoted(items: &[&str]) -> String {
    items
        .iter()
        .map(|s| format!("\"{s}\""))
        .collect::<Vec<_>>()
        .join(", ")
}

/// An entry of an array of tables: `[[load]] #2 "shake"` (1-based, with its name if it has one).
pub(super) fn item(table: &str, index: usize, name: Option<&String>) -> String {
    match name {
        Some(n) => format!("[[{table}]] #{} \"{n}\"", index + 1),
        None => format!("[[{table}]] #{}", index + 1),
    }
}

/// A key of an entry of an array of tables: `[[load]] #2 "shake", key `at``.
pub(super) fn entry(table: &str, index: usize, name: Option<&String>, key: &str) -> String {
    format!("{}, key `{key}`", item(table, index, name))
}
