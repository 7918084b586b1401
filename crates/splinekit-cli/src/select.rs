//! Loading an SWP file and picking one of its curves (`--curve NAME|INDEX`).

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, bail};
use glam::DVec3;
use splinekit::AnyCurve;
use splinekit_io::{SwpCurve, SwpDocument};

/// At most this many curves are listed in an "unknown curve" message.
const MAX_LISTED: usize = 20;

/// A curve picked from a file, compiled for the geometry core.
pub struct Selected<'a> {
    /// The curve as the file describes it.
    pub swp: &'a SwpCurve,
    /// Its name for output: the curve's name, or `#<index>` when anonymous.
    pub name: String,
    /// The compiled curve.
    pub curve: AnyCurve<DVec3>,
}

/// Reads and parses an SWP file. The error is the parser's own `FILE:LINE:COL: …` message
/// (or `FILE: cannot read file: …`), which already names the file.
pub fn load(path: &Path) -> anyhow::Result<SwpDocument> {
    Ok(SwpDocument::read(path)?)
}

/// Picks a curve of `doc` by `token`: a curve name, else a 0-based index (`2` or `#2`).
/// A name wins over an index. `None` picks the first curve.
pub fn select<'a>(doc: &'a SwpDocument, path: &Path, token: Option<&str>) -> anyhow::Result<Selected<'a>> {
    if doc.curves.is_empty() {
        bail!("{} has no curves", path.display());
    }
    let index = match token {
        None => 0,
        Some(token) => match find(doc, token) {
            Some(index) => index,
            None => bail!("no curve {token:?} in {}; {}", path.display(), list(doc)),
        },
    };
    let swp = &doc.curves[index];
    let name = swp.display_name(index);
    let curve = swp.to_curve().with_context(|| format!("curve {name} of {}", path.display()))?;
    Ok(Selected { swp, name, curve })
}

fn find(doc: &SwpDocument, token: &str) -> Option<usize> {
    if let Some(index) = doc.curve_index(token) {
        return Some(index);
    }
    let digits = token.strip_prefix('#').unwrap_or(token);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    digits.parse::<usize>().ok().filter(|&i| i < doc.curves.len())
}

/// `the file's 3 curves (index: name (kind)): 0: #0 (bez2), 1: profile (bsp2), …`
fn list(doc: &SwpDocument) -> String {
    let n = doc.curves.len();
    let mut text = format!("the file's {n} curve{} (index: name (kind)): ", if n == 1 { "" } else { "s" });
    for (i, c) in doc.curves.iter().enumerate().take(MAX_LISTED) {
        if i > 0 {
            text.push_str(", ");
        }
        let _ = write!(text, "{i}: {} ({})", c.display_name(i), c.keyword());
    }
    if n > MAX_LISTED {
        let _ = write!(text, ", … and {} more", n - MAX_LISTED);
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc() -> SwpDocument {
        let text = "bsp2 . 20 4 [0 0] [1 0] [1 1] [0 1]\n\
                    bsp2 2 20 4 [0 0] [1 0] [1 1] [0 1]\n\
                    circ ring 30 1\n";
        SwpDocument::parse(text, "t.swp").unwrap()
    }

    #[test]
    fn by_name_index_and_hash() {
        let d = doc();
        let p = Path::new("t.swp");
        assert_eq!(select(&d, p, None).unwrap().name, "#0");
        assert_eq!(select(&d, p, Some("ring")).unwrap().name, "ring");
        assert_eq!(select(&d, p, Some("0")).unwrap().name, "#0");
        assert_eq!(select(&d, p, Some("#0")).unwrap().name, "#0");
        // "2" is both a name (curve 1) and an index (curve 2): the name wins
        assert_eq!(select(&d, p, Some("2")).unwrap().name, "2");
        assert_eq!(select(&d, p, Some("#2")).unwrap().name, "ring");
    }

    #[test]
    fn unknown_lists_curves() {
        let d = doc();
        let p = Path::new("t.swp");
        for bad in ["nope", "3", "#9", "-1", "+1", ""] {
            let msg = format!("{:#}", select(&d, p, Some(bad)).err().unwrap());
            assert!(msg.contains("t.swp") && msg.contains("0: #0 (bsp2), 1: 2 (bsp2), 2: ring (circ)"), "{msg}");
        }
        let empty = SwpDocument::default();
        assert!(format!("{:#}", select(&empty, p, None).err().unwrap()).contains("no curves"));
    }
}
