//! The outer layer of a glTF file: JSON text, or a GLB container (a 12-byte
//! header, a JSON chunk, then an optional BIN chunk), checked byte by byte so
//! a truncated file gets a message saying how much is missing.

use crate::scene::LoadProblem;
use gltf::json::Root;

const GLB_MAGIC: &[u8; 4] = b"glTF";
const GLB_VERSION: u32 = 2;
const GLB_HEADER_BYTES: usize = 12;
const CHUNK_HEADER_BYTES: usize = 8;
/// Chunk types, the ASCII of "JSON" and "BIN\0" read as little-endian u32.
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

/// The parsed JSON and the GLB's binary chunk, if any.
pub(super) struct Container<'a> {
    pub root: Root,
    pub bin: Option<&'a [u8]>,
}

pub(super) fn parse(bytes: &[u8]) -> Result<Container<'_>, LoadProblem> {
    if bytes.starts_with(GLB_MAGIC) {
        let (json, bin) = split_glb(bytes)?;
        Ok(Container {
            root: parse_json(json)?,
            bin,
        })
    } else {
        Ok(Container {
            root: parse_json(bytes)?,
            bin: None,
        })
    }
}

fn u32_at(bytes: &[u8], offset: usize) -> Option<u32> {
    let word = bytes.get(offset..offset.checked_add(4)?)?;
    Some(u32::from_le_bytes([word[0], word[1], word[2], word[3]]))
}

/// The JSON and BIN chunks of a GLB; unknown chunk types are skipped, as
/// the format asks.
fn split_glb(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), LoadProblem> {
    let bad = |m: String| LoadProblem::BadGlb(m);
    let (Some(version), Some(length)) = (u32_at(bytes, 4), u32_at(bytes, 8)) else {
        return Err(bad(format!(
            "the file has {} bytes, less than the {GLB_HEADER_BYTES}-byte header",
            bytes.len()
        )));
    };
    if version != GLB_VERSION {
        return Err(bad(format!("GLB version {version}; only version 2 is supported")));
    }
    let length = length as usize;
    if length > bytes.len() {
        return Err(bad(format!(
            "the header says {length} bytes but the file has {}",
            bytes.len()
        )));
    }
    if length < GLB_HEADER_BYTES {
        return Err(bad(format!("the header gives a length of {length} bytes")));
    }
    let body = &bytes[..length];
    let mut offset = GLB_HEADER_BYTES;
    let (mut json, mut bin) = (None, None);
    let mut chunk = 0;
    while offset < body.len() {
        let (Some(chunk_len), Some(kind)) = (u32_at(body, offset), u32_at(body, offset + 4)) else {
            return Err(bad(format!("chunk {chunk} header is cut off at byte {offset}")));
        };
        let start = offset + CHUNK_HEADER_BYTES;
        let end = start
            .checked_add(chunk_len as usize)
            .filter(|&end| end <= body.len())
            .ok_or_else(|| {
                bad(format!(
                    "chunk {chunk} needs {chunk_len} bytes from byte {start} but the file ends at {}",
                    body.len()
                ))
            })?;
        let data = &body[start..end];
        match (chunk, kind) {
            (0, CHUNK_JSON) => json = Some(data),
            (0, _) => return Err(bad("the first chunk is not JSON".into())),
            (_, CHUNK_BIN) if bin.is_none() => bin = Some(data),
            (_, CHUNK_JSON | CHUNK_BIN) => {
                return Err(bad(format!("chunk {chunk} repeats a JSON or BIN chunk")));
            }
            _ => {}
        }
        offset = end;
        chunk += 1;
    }
    let json = json.ok_or_else(|| bad("no JSON chunk".into()))?;
    Ok((json, bin))
}

fn parse_json(text: &[u8]) -> Result<Root, LoadProblem> {
    // A UTF-8 byte-order mark is tolerated by most tools; serde_json is not.
    let text = text.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(text);
    match text.iter().find(|b| !b.is_ascii_whitespace()) {
        Some(b'{') => {}
        _ => {
            return Err(LoadProblem::NotGltf(
                "neither glTF JSON nor binary glTF (GLB)".into(),
            ));
        }
    }
    let mut value: serde_json::Value =
        serde_json::from_slice(text).map_err(|e| LoadProblem::NotGltf(e.to_string()))?;
    // glTF allows a scene without `nodes` (an empty scene); the json crate
    // requires the key, so an absent one is read as empty.
    if let Some(scenes) = value.get_mut("scenes").and_then(|s| s.as_array_mut()) {
        for scene in scenes.iter_mut().filter_map(|s| s.as_object_mut()) {
            scene.entry("nodes").or_insert_with(|| serde_json::json!([]));
        }
    }
    serde_json::from_value(value).map_err(|e| LoadProblem::NotGltf(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glb(json: &[u8], bin: Option<&[u8]>) -> Vec<u8> {
        let mut chunks = Vec::new();
        for (kind, data) in [(CHUNK_JSON, Some(json)), (CHUNK_BIN, bin)] {
            if let Some(data) = data {
                chunks.extend((data.len() as u32).to_le_bytes());
                chunks.extend(kind.to_le_bytes());
                chunks.extend(data);
            }
        }
        let mut out = GLB_MAGIC.to_vec();
        out.extend(GLB_VERSION.to_le_bytes());
        out.extend(((GLB_HEADER_BYTES + chunks.len()) as u32).to_le_bytes());
        out.extend(chunks);
        out
    }

    const MINIMAL: &[u8] = br#"{"asset":{"version":"2.0"}}"#;

    #[test]
    fn glb_chunks_are_split() {
        let bytes = glb(MINIMAL, Some(&[1, 2, 3, 4]));
        let c = parse(&bytes).unwrap();
        assert_eq!(c.bin, Some(&[1u8, 2, 3, 4][..]));
        assert_eq!(c.root.asset.version, "2.0");
    }

    #[test]
    fn every_truncation_of_a_glb_is_an_error() {
        let bytes = glb(MINIMAL, Some(&[0; 8]));
        for len in 0..bytes.len() {
            assert!(
                matches!(
                    parse(&bytes[..len]),
                    Err(LoadProblem::BadGlb(_) | LoadProblem::NotGltf(_))
                ),
                "{len}"
            );
        }
    }

    #[test]
    fn text_that_is_not_json_is_named() {
        assert!(matches!(parse(b"\x89PNG"), Err(LoadProblem::NotGltf(_))));
        assert!(parse(b"\xEF\xBB\xBF{\"asset\":{\"version\":\"2.0\"}}").is_ok());
    }
}
