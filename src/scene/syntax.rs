//! Reading a scene file's text into [`SceneFile`], with errors that name the key. The toml
//! crate reports a wrong type or an unknown key with a byte span only; this module finds the
//! key at that span (walking the document's spans with `toml_edit`) and says what is allowed
//! in words ("a number", "an array of strings", ...).
use super::checker::{entry, item};
use super::file::SceneFile;
use super::SceneError;
use std::ops::Range;
use toml_edit::{ImDocument, Item, Table, Value};

/// The arrays of tables of a scene file: their entries are named `[[load]] #2 "shake"`.
const ARRAYS_OF_TABLES: [&str; 7] = [
    "parameter",
    "support",
    "load",
    "sensor",
    "mass",
    "spring",
    "foundation",
];

pub(super) fn read(text: &str, file: &str) -> Result<SceneFile, SceneError> {
    toml::from_str(text).map_err(|e| {
        let span = e.span();
        let line = span
            .as_ref()
            .map(|s| text[..s.start.min(text.len())].matches('\n').count() + 1);
        let found = span.as_ref().and_then(|s| key_at(text, s.start));
        // `[sensor]` written for `[[sensor]]`.
        let array_of_tables = match &found {
            Some((path, _)) => match path.as_slice() {
                [Step::Key(k)] if ARRAYS_OF_TABLES.contains(&k.as_str()) => Some(k.as_str()),
                _ => None,
            },
            None => None,
        };
        let message = explain(e.message().trim(), array_of_tables);
        let (key, message) = match (found, line) {
            (Some((_, key)), Some(line)) => (key, format!("{message} (line {line})")),
            (None, Some(line)) => (format!("line {line}"), message),
            (_, None) => (String::new(), message),
        };
        SceneError {
            file: file.to_string(),
            key,
            message,
        }
    })
}

/// serde's "invalid type: string \"ten\", expected f64" in the words of the docs.
fn explain(message: &str, array_of_tables: Option<&str>) -> String {
    let Some(rest) = message.strip_prefix("invalid type: ") else {
        return message.to_string();
    };
    let Some((found, expected)) = rest.split_once(", expected ") else {
        return message.to_string();
    };
    let allowed = match (expected, array_of_tables) {
        ("f64", _) => "a number".to_string(),
        ("i64", _) => "an integer".to_string(),
        ("a sequence", Some(t)) => format!("an array of tables (write [[{t}]], not [{t}])"),
        // The only other array of the format: `fix`.
        ("a sequence", None) => "an array of strings (such as [\"u1\", \"u2\"])".to_string(),
        ("a boolean", _) => "true or false".to_string(),
        (e, _) if e.starts_with("struct ") || e.starts_with("a map") => "a table".to_string(),
        (e, _) => e.to_string(),
    };
    let found = found.replace('`', "");
    let found = match found.split_once(' ') {
        Some(("floating", v)) => format!("a number ({})", v.trim_start_matches("point ")),
        Some(("integer", v)) => format!("an integer ({v})"),
        Some(("string", v)) => format!("a string ({v})"),
        Some(("boolean", v)) => format!("a boolean ({v})"),
        _ if found == "map" => "a table".to_string(),
        _ if found == "sequence" => "an array".to_string(),
        _ => found,
    };
    format!("wrong type: {found} where {allowed} is allowed")
}

/// One step of a key path: a key of a table, or an entry of an array (of tables).
#[derive(Debug)]
enum Step {
    Key(String),
    Index(usize),
}

/// The key whose name or value covers byte `at` of the text, if any: its path and its name.
fn key_at(text: &str, at: usize) -> Option<(Vec<Step>, String)> {
    let doc = ImDocument::parse(text).ok()?;
    let mut path = Vec::new();
    if !in_table(doc.as_table(), at, &mut path) {
        return None;
    }
    let key = name(doc.as_table(), &path);
    Some((path, key))
}

fn covers(range: Option<Range<usize>>, at: usize) -> bool {
    range.is_some_and(|r| r.contains(&at) || (r.is_empty() && r.start == at))
}

/// Appends to `path` the innermost key of `table` at byte `at`; false if there is none.
fn in_table(table: &Table, at: usize, path: &mut Vec<Step>) -> bool {
    for (k, item) in table.iter() {
        let key_span = table.get_key_value(k).and_then(|(key, _)| key.span());
        path.push(Step::Key(k.to_string()));
        if in_item(item, at, path) || covers(key_span, at) {
            return true;
        }
        path.pop();
    }
    false
}

fn in_item(item: &Item, at: usize, path: &mut Vec<Step>) -> bool {
    match item {
        Item::None => false,
        Item::Value(v) => in_value(v, at, path),
        Item::Table(t) => in_table(t, at, path) || covers(t.span(), at),
        Item::ArrayOfTables(a) => {
            for (i, t) in a.iter().enumerate() {
                path.push(Step::Index(i));
                if in_table(t, at, path) || covers(t.span(), at) {
                    return true;
                }
                path.pop();
            }
            false
        }
    }
}

fn in_value(value: &Value, at: usize, path: &mut Vec<Step>) -> bool {
    if !covers(value.span(), at) {
        return false;
    }
    if let Value::InlineTable(t) = value {
        for (k, v) in t.iter() {
            let key_span = t.get_key_value(k).and_then(|(key, _)| key.span());
            path.push(Step::Key(k.to_string()));
            if in_value(v, at, path) || covers(key_span, at) {
                return true;
            }
            path.pop();
        }
    }
    // Inside an array the key is the array's: `fix = ["u1", 2]` is a wrong `fix`.
    true
}

/// A key path as the checker names keys: `geometry.L`, `experiment.step`,
/// `[[load]] #2 "shake", key `at``.
fn name(root: &Table, path: &[Step]) -> String {
    let dotted = |steps: &[Step]| {
        steps
            .iter()
            .map(|s| match s {
                Step::Key(k) => k.clone(),
                Step::Index(i) => format!("#{}", i + 1),
            })
            .collect::<Vec<_>>()
            .join(".")
    };
    if let [Step::Key(table), Step::Index(i), rest @ ..] = path {
        if ARRAYS_OF_TABLES.contains(&table.as_str()) {
            let entry_name = root
                .get(table)
                .and_then(Item::as_array_of_tables)
                .and_then(|a| a.get(*i))
                .and_then(|t| t.get("name"))
                .and_then(Item::as_str)
                .map(str::to_string);
            if rest.is_empty() {
                return item(table, *i, entry_name.as_ref());
            }
            return entry(table, *i, entry_name.as_ref(), &dotted(rest));
        }
    }
    dotted(path)
}
