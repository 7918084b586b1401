//! Byte-level mutation of seed files: flipped bits, bytes set to interesting values,
//! inserted, deleted, duplicated and swapped chunks, numbers replaced by extreme ones,
//! 4- and 8-byte words overwritten with interesting integers and float bit patterns (for
//! the binary formats), truncation, and splices of two seeds.

use crate::rng::Rng;
use crate::values::EXTREMES;

/// Bytes that often matter to a parser.
const INTERESTING_BYTES: [u8; 18] =
    [0, 0xff, 0x7f, 0x80, b'\n', b'\r', b' ', b'-', b'+', b'.', b'e', b'9', b'0', b'[', b']', b'#', b'/', b'"'];

/// Words that often matter to a binary reader (counts, lengths, offsets, floats).
const INTERESTING_U32: [u32; 10] = [0, 1, 2, 3, 0x7f, 0xff, 0xffff, 0x7fff_ffff, 0x8000_0000, u32::MAX];

/// Text that often matters to a text reader.
const INTERESTING_TEXT: [&str; 16] = [
    "nan",
    "inf",
    "-0",
    "1e309",
    "99999999999999999999",
    "-1",
    "0",
    "1000000",
    "4294967296",
    ".",
    "[",
    "]",
    "\r\n",
    "#",
    "é",
    "\u{feff}",
];

/// `seed` changed by 1 to 8 mutations; `other` is spliced in now and then.
pub fn mutate(rng: &mut Rng, seed: &[u8], other: &[u8]) -> Vec<u8> {
    let mut data = seed.to_vec();
    let count = rng.range(1, 8);
    for _ in 0..count {
        mutate_once(rng, &mut data, other);
    }
    data
}

/// A random position in `0..=len`.
fn at(rng: &mut Rng, len: usize) -> usize {
    rng.below(len + 1)
}

/// A chunk length: mostly short, now and then long.
fn chunk(rng: &mut Rng, len: usize) -> usize {
    if len == 0 {
        return 0;
    }
    if rng.chance(0.8) { rng.range(1, 8.min(len)) } else { rng.range(1, len) }
}

fn mutate_once(rng: &mut Rng, data: &mut Vec<u8>, other: &[u8]) {
    let len = data.len();
    match rng.below(12) {
        0 if len > 0 => {
            let i = rng.below(len);
            data[i] ^= 1 << rng.below(8);
        }
        1 if len > 0 => {
            let i = rng.below(len);
            data[i] = *rng.pick(&INTERESTING_BYTES);
        }
        2 => {
            let i = at(rng, len);
            let n = chunk(rng, 16).max(1);
            let bytes: Vec<u8> = (0..n).map(|_| rng.next_u64() as u8).collect();
            data.splice(i..i, bytes);
        }
        3 if len > 0 => {
            let i = rng.below(len);
            let n = chunk(rng, len - i);
            data.drain(i..i + n);
        }
        4 if len > 0 => {
            // duplicate a chunk somewhere else (repeated statements, records, vertices)
            let i = rng.below(len);
            let n = chunk(rng, len - i);
            let piece = data[i..i + n].to_vec();
            let j = at(rng, len);
            data.splice(j..j, piece);
        }
        5 if len > 1 => {
            let (i, j) = (rng.below(len), rng.below(len));
            let n = chunk(rng, len - i.max(j));
            for k in 0..n {
                data.swap(i + k, j + k);
            }
        }
        6 => replace_number(rng, data),
        7 if len >= 4 => {
            let i = rng.below(len - 3);
            let word = if rng.chance(0.5) {
                *rng.pick(&INTERESTING_U32)
            } else {
                (*rng.pick(&EXTREMES) as f32).to_bits() ^ if rng.chance(0.2) { 0x7fc0_0000 } else { 0 }
            };
            let bytes = if rng.chance(0.8) { word.to_le_bytes() } else { word.to_be_bytes() };
            data[i..i + 4].copy_from_slice(&bytes);
        }
        8 if len >= 8 => {
            let i = rng.below(len - 7);
            let x = if rng.chance(0.8) { *rng.pick(&EXTREMES) } else { f64::NAN };
            data[i..i + 8].copy_from_slice(&x.to_le_bytes());
        }
        9 => {
            let i = at(rng, len);
            let text = *rng.pick(&INTERESTING_TEXT);
            data.splice(i..i, text.bytes());
        }
        10 if len > 0 => {
            let n = at(rng, len);
            data.truncate(n);
        }
        11 if !other.is_empty() => {
            // splice: the head of this seed and the tail of the other
            let i = at(rng, len);
            let j = rng.below(other.len());
            data.truncate(i);
            data.extend_from_slice(&other[j..]);
        }
        _ => {
            let i = at(rng, len);
            data.insert(i, *rng.pick(&INTERESTING_BYTES));
        }
    }
}

/// Replaces a decimal number in the text by another: extreme, huge, negative, malformed.
fn replace_number(rng: &mut Rng, data: &mut Vec<u8>) {
    let starts: Vec<usize> = (0..data.len())
        .filter(|&i| {
            data[i].is_ascii_digit() && (i == 0 || !data[i - 1].is_ascii_alphanumeric() && data[i - 1] != b'.')
        })
        .collect();
    if starts.is_empty() {
        return;
    }
    let i = *rng.pick(&starts);
    let end = (i..data.len())
        .find(|&k| !matches!(data[k], b'0'..=b'9' | b'.' | b'e' | b'E' | b'-' | b'+'))
        .unwrap_or(data.len());
    let text = match rng.below(4) {
        0 => format!("{:e}", rng.pick(&EXTREMES)),
        1 => format!("{}", rng.pick(&EXTREMES)),
        2 => (*rng.pick(&INTERESTING_TEXT)).to_owned(),
        _ => format!("{}", rng.next_u64() >> rng.below(64)),
    };
    data.splice(i..end, text.bytes());
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mutations_change_and_stay_bounded() {
        let seed = b"bez2 . 20 4 [0 0] [1 1] [2 0] [3 1]\n".to_vec();
        let mut changed = 0;
        for i in 0..500 {
            let mut rng = Rng::for_case(3, i);
            let out = mutate(&mut rng, &seed, b"circ c 10 1\n");
            assert!(out.len() <= 256 * seed.len() + 2000, "{}", out.len());
            changed += usize::from(out != seed);
        }
        assert!(changed > 450, "{changed}");
    }
}
