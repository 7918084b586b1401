//! The binary container of a `.glb`: the header, the JSON and BIN chunks, and the buffers
//! (the BIN chunk or base64 `data:` URIs).

use std::borrow::Cow;

use gltf_json as json;

use super::super::MeshIoError;
use super::super::load::{self, ReadWarningKind, Warnings};
use super::invalid;
use crate::mesh::glb::{CHUNK_BIN, CHUNK_JSON, MAGIC};

/// Size of the file header (magic, version, length).
pub(super) const HEADER: usize = 12;
/// Size of a chunk header (length, type).
pub(super) const CHUNK_HEADER: usize = 8;

/// The little-endian `u32` at `at` (which is in bounds).
pub(super) fn u32_at(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
}

/// The chunks of a `.glb`.
pub(super) struct Chunks<'a> {
    /// Where the JSON chunk's data starts in the file.
    pub(super) json_at: usize,
    pub(super) json: &'a [u8],
    pub(super) bin: Option<&'a [u8]>,
}

/// Checks the header and splits the chunks.
pub(super) fn chunks<'a>(bytes: &'a [u8], origin: &str, warnings: &mut Warnings) -> Result<Chunks<'a>, MeshIoError> {
    let size = bytes.len();
    if size < HEADER {
        if bytes.first() == Some(&b'{') {
            return Err(not_binary(origin));
        }
        return Err(load::truncated(origin, format!("a 12-byte binary glTF header (the file has {size} bytes)")));
    }
    if &bytes[..4] != MAGIC {
        let text = bytes.trim_ascii_start();
        if text.first() == Some(&b'{') {
            return Err(not_binary(origin));
        }
        return Err(invalid(
            origin,
            "byte 0",
            format!("found \"{}\", expected glTF (the magic number of binary glTF)", bytes[..4].escape_ascii()),
        ));
    }
    let version = u32_at(bytes, 4);
    if version != 2 {
        return Err(invalid(origin, "byte 4", format!("found version {version}, expected version 2 (glTF 2.0)")));
    }
    let length = u32_at(bytes, 8) as usize;
    if length < HEADER + CHUNK_HEADER {
        return Err(invalid(
            origin,
            "byte 8",
            format!("found a total length of {length} bytes, expected at least 20 (the header and a JSON chunk)"),
        ));
    }
    if length > size {
        return Err(load::truncated(
            origin,
            format!("{length} bytes (the length in the binary glTF header), found {size}"),
        ));
    }
    if length < size {
        warnings.push(0, ReadWarningKind::TrailingBytes { count: size - length });
    }
    let bytes = &bytes[..length];
    let mut at = HEADER;
    let mut json = None;
    let mut bin = None;
    let mut index = 0;
    while at < length {
        if length - at < CHUNK_HEADER {
            return Err(load::truncated(
                origin,
                format!("the 8-byte header of chunk {index} at byte {at} (the file has {length} bytes)"),
            ));
        }
        let chunk_length = u32_at(bytes, at) as usize;
        let kind = &bytes[at + 4..at + 8];
        let start = at + CHUNK_HEADER;
        if chunk_length > length - start {
            return Err(load::truncated(
                origin,
                format!(
                    "the {chunk_length} bytes of chunk {index} (\"{}\") at byte {start}, found {}",
                    kind.escape_ascii(),
                    length - start
                ),
            ));
        }
        let data = &bytes[start..start + chunk_length];
        if index == 0 {
            if kind != CHUNK_JSON {
                return Err(invalid(
                    origin,
                    format!("chunk 0 at byte {at}"),
                    format!("found chunk type \"{}\", expected JSON (the first chunk)", kind.escape_ascii()),
                ));
            }
            json = Some((start, data));
        } else if kind == CHUNK_BIN && bin.is_none() {
            if index != 1 {
                return Err(invalid(
                    origin,
                    format!("chunk {index} at byte {at}"),
                    "found a BIN chunk, expected it to be the second chunk",
                ));
            }
            bin = Some(data);
        }
        // Other chunk types are skipped, as the specification asks.
        at = start + chunk_length;
        index += 1;
    }
    // `length >= 20`, so the loop saw chunk 0.
    let (json_at, json) = json.unwrap_or((HEADER, &[]));
    Ok(Chunks { json_at, json, bin })
}

/// The error for a text `.gltf` file read as binary.
pub(super) fn not_binary(origin: &str) -> MeshIoError {
    invalid(
        origin,
        "byte 0",
        "found JSON text, expected binary glTF starting with glTF (text .gltf files are not supported)",
    )
}

/// Parses the JSON chunk, which starts at byte `json_at` of the file.
pub(super) fn parse_json(bytes: &[u8], json_at: usize, origin: &str) -> Result<json::Root, MeshIoError> {
    // Padding is spaces; some writers pad with NULs.
    let end = bytes.iter().rposition(|&b| b != 0 && !b.is_ascii_whitespace()).map_or(0, |e| e + 1);
    let bytes = &bytes[..end];
    json::Root::from_slice(bytes).map_err(|e| {
        let message = e.to_string();
        let suffix = format!(" at line {} column {}", e.line(), e.column());
        let message = message.strip_suffix(&suffix).unwrap_or(&message);
        let at = if e.line() == 0 {
            String::from("JSON chunk")
        } else {
            let byte = json_at + byte_offset(bytes, e.line(), e.column());
            format!("JSON chunk line {}, column {} (byte {byte})", e.line(), e.column())
        };
        invalid(origin, at, format!("invalid glTF JSON: {message}"))
    })
}

/// The byte offset of 1-based `line` and `column` (serde_json's: the column counts bytes,
/// and is 0 before the first byte of a line).
pub(super) fn byte_offset(text: &[u8], line: usize, column: usize) -> usize {
    let line_start = if line <= 1 {
        0
    } else {
        text.iter().enumerate().filter(|&(_, &b)| b == b'\n').nth(line - 2).map_or(text.len(), |(i, _)| i + 1)
    };
    (line_start + column.saturating_sub(1)).min(text.len())
}

/// A resolved buffer, or where and why it cannot be read (reported if an accessor uses it).
pub(super) type Buffer<'a> = Result<Cow<'a, [u8]>, (String, String)>;

/// The bytes of buffer `i`: the `BIN` chunk for the first buffer without `uri`, or a base64
/// `data:` URI.
pub(super) fn resolve_buffer<'a>(i: usize, buffer: &json::Buffer, bin: Option<&'a [u8]>) -> Buffer<'a> {
    let length = buffer.byte_length.0;
    let data: Cow<'a, [u8]> = match (&buffer.uri, bin) {
        (None, Some(bin)) if i == 0 => Cow::Borrowed(bin),
        (None, None) if i == 0 => {
            return Err((
                String::from("buffers[0]"),
                String::from("found a buffer without uri and no BIN chunk, expected a BIN chunk holding it"),
            ));
        }
        (None, _) => {
            return Err((
                format!("buffers[{i}]"),
                String::from("found a buffer without uri, expected a uri (only the first buffer is the BIN chunk)"),
            ));
        }
        (Some(uri), _) => match uri.strip_prefix("data:") {
            Some(rest) => {
                let Some((media, text)) = rest.split_once(',') else {
                    return Err((format!("buffers[{i}].uri"), String::from("found a data URI without a comma")));
                };
                if !media.ends_with(";base64") {
                    return Err((
                        format!("buffers[{i}].uri"),
                        format!("found a data URI \"data:{media},…\", expected a base64 one (data:…;base64,…)"),
                    ));
                }
                match decode_base64(text.as_bytes()) {
                    Some(bytes) => Cow::Owned(bytes),
                    None => {
                        return Err((
                            format!("buffers[{i}].uri"),
                            String::from("found invalid base64 in the data URI, expected base64 text"),
                        ));
                    }
                }
            }
            None => {
                let shown: String = uri.chars().take(60).collect();
                return Err((
                    format!("buffers[{i}].uri"),
                    format!(
                        "external buffer {shown:?} is not supported: only .glb with embedded buffers (the BIN chunk or base64 data: URIs)"
                    ),
                ));
            }
        },
    };
    if length > data.len() as u64 {
        let source = if buffer.uri.is_none() { "the BIN chunk" } else { "the data URI" };
        return Err((
            format!("buffers[{i}].byteLength"),
            format!("found {length} bytes, expected at most {} (the size of {source})", data.len()),
        ));
    }
    // `length <= data.len()`, so it fits in usize.
    Ok(match data {
        Cow::Borrowed(b) => Cow::Borrowed(&b[..length as usize]),
        Cow::Owned(mut b) => {
            b.truncate(length as usize);
            Cow::Owned(b)
        }
    })
}

/// Decodes standard or URL-safe base64 (padding optional, whitespace ignored).
pub(super) fn decode_base64(text: &[u8]) -> Option<Vec<u8>> {
    let text = text.trim_ascii_end();
    let text = text.strip_suffix(b"==").or_else(|| text.strip_suffix(b"=")).unwrap_or(text);
    let mut out = Vec::with_capacity(text.len() / 4 * 3 + 2);
    let (mut acc, mut bits, mut digits) = (0u32, 0u32, 0usize);
    for &c in text {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            c if c.is_ascii_whitespace() => continue,
            _ => return None,
        };
        digits += 1;
        acc = (acc << 6) | u32::from(v);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    (digits % 4 != 1).then_some(out)
}
