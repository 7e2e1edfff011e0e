//! `fmuResourceLocation`: a URI (RFC 3986) to the unzipped `resources/` folder. Hosts send
//! `file:///abs/path`, `file:/abs/path` or `file://localhost/abs/path`, percent-encoded.
use std::path::PathBuf;

/// The local directory a `file:` URI names, or why it names none.
pub fn file_uri_to_path(uri: &str) -> Result<PathBuf, String> {
    let rest = uri
        .strip_prefix("file:")
        .or_else(|| uri.strip_prefix("FILE:"))
        .ok_or_else(|| format!("\"{uri}\" is not a file: URI"))?;
    // "file:///p" and "file://localhost/p" carry an (empty or local) authority; "file:/p" none.
    let path = match rest.strip_prefix("//") {
        Some(after) => {
            let slash = after.find('/').unwrap_or(after.len());
            let host = &after[..slash];
            if !(host.is_empty() || host.eq_ignore_ascii_case("localhost")) {
                return Err(format!("\"{uri}\" names the remote host \"{host}\""));
            }
            &after[slash..]
        }
        None => rest,
    };
    if !path.starts_with('/') {
        return Err(format!("\"{uri}\" does not hold an absolute path"));
    }
    let decoded = percent_decode(path).ok_or_else(|| format!("\"{uri}\": bad percent-encoding"))?;
    // A Windows drive path arrives as "/C:/dir".
    let decoded = match decoded.as_bytes() {
        [b'/', drive, b':', ..] if cfg!(windows) && drive.is_ascii_alphabetic() => {
            decoded[1..].to_string()
        }
        _ => decoded,
    };
    Ok(PathBuf::from(decoded))
}

/// `%XX` decoding; `None` for a truncated or non-hex escape or a result that is not UTF-8.
fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes.get(i + 1..i + 3)?;
            let hex = std::str::from_utf8(hex).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forms_of_file_uris() {
        let p = |s: &str| file_uri_to_path(s).map(|p| p.to_string_lossy().into_owned());
        assert_eq!(
            p("file:///tmp/a%20b/resources").unwrap(),
            "/tmp/a b/resources"
        );
        assert_eq!(p("file:/tmp/x").unwrap(), "/tmp/x");
        assert_eq!(p("file://localhost/tmp/x/").unwrap(), "/tmp/x/");
        assert_eq!(p("file:///t%C3%A9st").unwrap(), "/t\u{e9}st");
        assert!(p("http://host/x").is_err());
        assert!(p("file://remote/x").is_err());
        assert!(p("file:relative").is_err());
        assert!(p("file:///bad%2").is_err());
        assert!(p("file:///bad%zz").is_err());
    }
}
