//! The bytes a glTF file points to: buffers (the GLB's binary chunk, base64
//! data URIs or files beside the scene) and base-colour images.

use crate::scene::{LoadProblem, Texture};
use gltf::json::Root;
use std::borrow::Cow;
use std::path::Path;

/// Largest image side (texels) the lab decodes: the GPUs it targets cannot
/// sample a larger 2D texture, and it bounds what a corrupt header can make
/// the decoder allocate.
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// Every buffer of the file, each at least as long as its `byteLength`.
pub(super) fn load_buffers<'a>(
    root: &Root,
    bin: Option<&'a [u8]>,
    base_dir: Option<&Path>,
) -> Result<Vec<Cow<'a, [u8]>>, LoadProblem> {
    let mut buffers = Vec::with_capacity(root.buffers.len());
    for (i, buffer) in root.buffers.iter().enumerate() {
        let what = describe("buffer", i, buffer.uri.as_deref());
        let data = match (&buffer.uri, bin) {
            (Some(uri), _) => Cow::Owned(read_uri(uri, base_dir, Kind::Buffer).map_err(|reason| {
                LoadProblem::MissingData {
                    what: what.clone(),
                    reason,
                }
            })?),
            // Only the first buffer may stand for the GLB's binary chunk.
            (None, Some(bin)) if i == 0 => Cow::Borrowed(bin),
            (None, _) => {
                return Err(LoadProblem::MissingData {
                    what,
                    reason: "it has no uri and the file has no GLB binary chunk for it".into(),
                });
            }
        };
        let declared = buffer.byte_length.0;
        if (data.len() as u64) < declared {
            return Err(LoadProblem::OutOfRange {
                what,
                detail: format!("byteLength is {declared} but only {} bytes are there", data.len()),
            });
        }
        buffers.push(data);
    }
    Ok(buffers)
}

/// "buffer 2 'scene.bin'", shortening data URIs.
pub(super) fn describe(kind: &str, index: usize, uri: Option<&str>) -> String {
    match uri {
        Some(uri) if uri.starts_with("data:") => format!("{kind} {index} (data URI)"),
        Some(uri) => format!("{kind} {index} '{uri}'"),
        None => format!("{kind} {index}"),
    }
}

/// What a URI points to, which bounds how much of a file is read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Buffer,
    Image,
}

/// The bytes behind a URI: a base64 data URI, or a path relative to the
/// scene's folder (percent-encoded, as URIs are), a regular file within
/// the size limit of its kind.
pub(super) fn read_uri(uri: &str, base_dir: Option<&Path>, kind: Kind) -> Result<Vec<u8>, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_media_type, payload) = rest
            .split_once(";base64,")
            .ok_or("only base64 data URIs are supported")?;
        // Padding is optional in practice; decoding without it accepts both.
        return base64::decode_config(payload.trim().trim_end_matches('='), base64::STANDARD_NO_PAD)
            .map_err(|e| format!("bad base64 data: {e}"));
    }
    if has_scheme(uri) {
        return Err("only relative paths and data: URIs are supported".into());
    }
    let decoded = urlencoding::decode_binary(uri.as_bytes());
    let relative =
        std::str::from_utf8(&decoded).map_err(|_| "the path is not UTF-8 once decoded".to_string())?;
    let base_dir = base_dir.ok_or("an embedded scene cannot refer to files")?;
    let path = base_dir.join(relative);
    let (limit, what) = match kind {
        Kind::Buffer => (crate::input::BUFFER_LIMIT_BYTES, "a buffer"),
        Kind::Image => (crate::input::IMAGE_LIMIT_BYTES, "an image"),
    };
    crate::input::read_bounded(&path, limit, what).map_err(|e| format!("'{}': {e}", path.display()))
}

/// `scheme:` at the start of a URI (RFC 3986: a letter, then letters,
/// digits, '+', '-' or '.').
fn has_scheme(uri: &str) -> bool {
    match uri.split_once(':') {
        Some((scheme, _)) => {
            let mut chars = scheme.chars();
            chars.next().is_some_and(|c| c.is_ascii_alphabetic())
                && chars.all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'))
        }
        None => false,
    }
}

/// Decodes a PNG or JPEG into sRGB RGBA8.
pub(super) fn decode_image(bytes: &[u8]) -> Result<Texture, String> {
    let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| e.to_string())?;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_IMAGE_SIDE);
    limits.max_image_height = Some(MAX_IMAGE_SIDE);
    reader.limits(limits);
    let rgba = reader.decode().map_err(|e| e.to_string())?.to_rgba8();
    Ok(Texture {
        width: rgba.width(),
        height: rgba.height(),
        rgba8: rgba.into_raw(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_uris_decode_with_or_without_padding() {
        assert_eq!(
            read_uri("data:application/octet-stream;base64,AAEC", None, Kind::Buffer).unwrap(),
            [0, 1, 2]
        );
        assert_eq!(read_uri("data:;base64,AAE=", None, Kind::Buffer).unwrap(), [0, 1]);
        assert_eq!(read_uri("data:;base64,AAE", None, Kind::Buffer).unwrap(), [0, 1]);
        assert!(read_uri("data:text/plain,hello", None, Kind::Buffer).is_err());
        assert!(read_uri("data:;base64,@@@", None, Kind::Buffer).is_err());
    }

    #[test]
    fn only_relative_paths_and_data_uris() {
        assert!(has_scheme("https://example.com/a.bin"));
        assert!(has_scheme("file:///tmp/a.bin"));
        assert!(!has_scheme("a%20b.bin") && !has_scheme("dir/a.bin"));
        assert!(read_uri("https://example.com/a.bin", Some(Path::new(".")), Kind::Buffer).is_err());
        assert!(
            read_uri("a.bin", None, Kind::Buffer)
                .unwrap_err()
                .contains("embedded")
        );
    }

    #[test]
    fn percent_encoded_paths_are_decoded() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("a b.bin"), [7u8]).unwrap();
        assert_eq!(
            read_uri("a%20b.bin", Some(dir.path()), Kind::Buffer).unwrap(),
            [7]
        );
        let missing = read_uri("nope.bin", Some(dir.path()), Kind::Buffer).unwrap_err();
        assert!(missing.contains("nope.bin"), "{missing}");
    }

    #[test]
    fn a_uri_naming_a_device_fails_fast() {
        let dev = read_uri(
            "../../../../../../../../dev/zero",
            Some(Path::new("/tmp")),
            Kind::Buffer,
        );
        assert!(dev.unwrap_err().contains("not a regular file"));
    }
}
