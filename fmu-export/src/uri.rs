//! The FMU's resource folder as the host gives it: a `file://` URI
//! (`fmuResourceLocation`, FMI 2.0), read back as a local path.

use std::path::PathBuf;

/// The local path of a `file://` URI (percent-decoded).
pub(crate) fn path_of_uri(uri: &str) -> Result<PathBuf, String> {
    let rest = uri
        .strip_prefix("file://")
        .or_else(|| uri.strip_prefix("file:"))
        .ok_or_else(|| format!("fmuResourceLocation `{uri}`: expected a file:// URI"))?;
    let rest = rest.strip_prefix("localhost").unwrap_or(rest);
    let bytes = rest.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%'
            && i + 2 < bytes.len()
            && let Ok(b) = u8::from_str_radix(
                std::str::from_utf8(&bytes[i + 1..i + 3]).unwrap_or("zz"),
                16,
            )
        {
            out.push(b);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    Ok(PathBuf::from(String::from_utf8_lossy(&out).into_owned()))
}

#[cfg(test)]
mod tests {
    use super::path_of_uri;
    use std::path::Path;

    #[test]
    fn a_file_uri_is_its_path_percent_decoded() {
        let path = |uri: &str| path_of_uri(uri).expect(uri);
        assert_eq!(
            path("file:///tmp/a%20b/resources"),
            Path::new("/tmp/a b/resources")
        );
        assert_eq!(path("file://localhost/tmp/r"), Path::new("/tmp/r"));
        assert_eq!(path("file:/tmp/r"), Path::new("/tmp/r"));
        // A lone or malformed escape stays as written.
        assert_eq!(path("file:///tmp/100%"), Path::new("/tmp/100%"));
        assert_eq!(path("file:///tmp/%zz"), Path::new("/tmp/%zz"));
    }

    #[test]
    fn another_scheme_is_refused_naming_the_uri() {
        let error = path_of_uri("http://host/r").expect_err("not a file URI");
        assert!(
            error.contains("http://host/r") && error.contains("file://"),
            "{error}"
        );
    }
}
