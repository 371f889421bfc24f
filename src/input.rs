//! Reading user files with a bound: only regular files (a device, a FIFO or
//! a folder is refused before a byte is read) and never more bytes than the
//! kind of file can sensibly hold, so `--scene /dev/zero` or a file that
//! keeps growing fails fast instead of filling the memory.

use std::io::{Error, ErrorKind, Read};
use std::path::Path;

/// A glTF or GLB scene (a GLB cannot exceed 4 GiB; data URIs live inside).
pub const SCENE_LIMIT_BYTES: u64 = 2 << 30;
/// One external buffer a glTF file names.
pub const BUFFER_LIMIT_BYTES: u64 = 2 << 30;
/// One external image (PNG or JPEG) a glTF file names.
pub const IMAGE_LIMIT_BYTES: u64 = 256 << 20;
/// A settings file (a few kilobytes when the app writes it).
pub const SETTINGS_LIMIT_BYTES: u64 = 1 << 20;
/// A sweep file for `lumlab report`.
pub const SWEEP_LIMIT_BYTES: u64 = 1 << 20;

/// `text` with its line breaks and other control characters escaped (`\n`),
/// for a message that quotes what a user or a file wrote: the message
/// stays one line whatever that text holds.
pub fn escape_controls(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_debug().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// `x` as a message shows it: plainly between 10⁻⁴ and 10⁷ (0.5, 179,
/// 1000000), in exponent form past them (1e32, -1e12, 1.8398786e34), so
/// that a range's bound reads as written instead of as 33 digits; the
/// shortest digits that give back the same f32 either way.
pub fn compact_number(x: f32) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e7).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// A range `min … max`, its bounds as [`compact_number`] shows them.
pub fn compact_range(min: f32, max: f32) -> String {
    format!("{} … {}", compact_number(min), compact_number(max))
}

/// Three numbers as [`compact_number`] shows them: `[0, 0, 2e12]`.
pub fn compact_numbers(v: [f32; 3]) -> String {
    format!("[{}]", v.map(compact_number).join(", "))
}

/// The bytes of the regular file at `path`, at most `limit` of them;
/// `what` names the kind of file in the message ("a settings file").
pub fn read_bounded(path: &Path, limit: u64, what: &str) -> std::io::Result<Vec<u8>> {
    // The type is checked before opening: opening a FIFO would block.
    check_regular(&std::fs::metadata(path)?)?;
    let file = std::fs::File::open(path)?;
    let metadata = file.metadata()?;
    check_regular(&metadata)?;
    if metadata.len() > limit {
        return Err(too_large(limit, what));
    }
    let mut bytes = Vec::with_capacity(metadata.len() as usize);
    // One byte past the limit tells a file that grew while being read.
    file.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(limit, what));
    }
    Ok(bytes)
}

/// As [`read_bounded`], for text that must be UTF-8.
pub fn read_text_bounded(path: &Path, limit: u64, what: &str) -> std::io::Result<String> {
    let bytes = read_bounded(path, limit, what)?;
    String::from_utf8(bytes).map_err(|_| Error::new(ErrorKind::InvalidData, "not UTF-8 text"))
}

fn check_regular(metadata: &std::fs::Metadata) -> std::io::Result<()> {
    let kind = metadata.file_type();
    if kind.is_file() {
        return Ok(());
    }
    let what = if kind.is_dir() {
        "a folder"
    } else {
        "a device, FIFO or socket"
    };
    Err(Error::new(
        ErrorKind::InvalidInput,
        format!("not a regular file ({what})"),
    ))
}

fn too_large(limit: u64, what: &str) -> Error {
    Error::new(
        ErrorKind::FileTooLarge,
        format!("larger than the {} limit for {what}", human_bytes(limit)),
    )
}

/// 2 GiB, 256 MiB, 1 MiB, 512 bytes.
pub fn human_bytes(bytes: u64) -> String {
    const UNITS: [(&str, u64); 3] = [("GiB", 1 << 30), ("MiB", 1 << 20), ("KiB", 1 << 10)];
    for (unit, size) in UNITS {
        if bytes >= size {
            let value = bytes as f64 / size as f64;
            return if value.fract() == 0.0 {
                format!("{value} {unit}")
            } else {
                format!("{value:.1} {unit}")
            };
        }
    }
    format!("{bytes} bytes")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quoted_text_stays_on_one_line() {
        assert_eq!(escape_controls("a\nb\tc\u{7}é '"), "a\\nb\\tc\\u{7}é '");
        assert_eq!(escape_controls("plain"), "plain");
    }

    #[test]
    fn numbers_read_as_written() {
        assert_eq!(compact_number(1e32), "1e32");
        assert_eq!(compact_number(-1e12), "-1e12");
        assert_eq!(compact_number(1.8398786e34), "1.8398786e34");
        assert_eq!(compact_number(1e6), "1000000");
        assert_eq!(compact_number(179.0), "179");
        assert_eq!(compact_number(0.99), "0.99");
        assert_eq!(compact_number(0.0), "0");
        assert_eq!(compact_number(2.5e-7), "2.5e-7");
        assert_eq!(compact_number(f32::NAN), "NaN");
        assert_eq!(compact_numbers([0.0, -0.5, 3e12]), "[0, -0.5, 3e12]");
        assert_eq!(compact_range(-1e12, 1e12), "-1e12 … 1e12");
    }

    #[test]
    fn devices_and_folders_are_refused_before_reading() {
        let zero = read_bounded(Path::new("/dev/zero"), 1 << 20, "a test file");
        assert!(zero.unwrap_err().to_string().starts_with("not a regular file"));
        let dir = tempfile::tempdir().unwrap();
        let folder = read_bounded(dir.path(), 10, "a test file").unwrap_err();
        assert_eq!(folder.to_string(), "not a regular file (a folder)");
    }

    #[test]
    fn a_file_over_the_limit_is_refused_without_reading_it() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("big");
        // Sparse: 1 GiB that takes no disk and would take a while to read.
        std::fs::File::create(&path).unwrap().set_len(1 << 30).unwrap();
        let error = read_bounded(&path, 1 << 20, "a settings file").unwrap_err();
        assert_eq!(
            error.to_string(),
            "larger than the 1 MiB limit for a settings file"
        );
        std::fs::write(&path, b"abc").unwrap();
        assert_eq!(read_bounded(&path, 3, "x").unwrap(), b"abc");
        assert!(read_bounded(&path, 2, "x").is_err());
    }

    #[test]
    fn sizes_read_like_people_write_them() {
        assert_eq!(human_bytes(2 << 30), "2 GiB");
        assert_eq!(human_bytes(1536 << 20), "1.5 GiB");
        assert_eq!(human_bytes(100), "100 bytes");
    }
}
