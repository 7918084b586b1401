//! [`Image`]: an opaque RGBA8 picture, its PNG encoding, and [`ImageSize`] (`WxH`).

use std::fmt;
use std::path::Path;
use std::str::FromStr;

use crate::RenderError;

/// The largest width or height [`ImageSize`] accepts.
pub const MAX_SIDE: u32 = 8192;

/// An sRGB colour, 8 bits per channel.
pub type Rgb = [u8; 3];

/// A picture: `width × height` pixels of sRGB RGBA, 8 bits per channel, row by row from the
/// top left. Rendered images are opaque (alpha 255).
#[derive(Clone, PartialEq, Eq)]
pub struct Image {
    width: u32,
    height: u32,
    data: Vec<u8>,
}

impl fmt::Debug for Image {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Image").field("width", &self.width).field("height", &self.height).finish_non_exhaustive()
    }
}

impl Image {
    /// An image filled with one opaque colour.
    #[must_use]
    pub fn filled(size: ImageSize, colour: Rgb) -> Self {
        let [r, g, b] = colour;
        let n = size.num_pixels();
        let mut data = Vec::with_capacity(4 * n);
        for _ in 0..n {
            data.extend_from_slice(&[r, g, b, 255]);
        }
        Self { width: size.width, height: size.height, data }
    }

    /// An image from RGBA8 bytes (`4 × width × height` of them), or `None` if the length is wrong.
    #[must_use]
    pub fn from_rgba(width: u32, height: u32, data: Vec<u8>) -> Option<Self> {
        (data.len() as u64 == 4 * u64::from(width) * u64::from(height)).then_some(Self { width, height, data })
    }

    /// Width in pixels.
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The size.
    #[must_use]
    pub fn size(&self) -> ImageSize {
        ImageSize { width: self.width, height: self.height }
    }

    /// The RGBA8 bytes, row by row from the top left.
    #[must_use]
    pub fn as_rgba(&self) -> &[u8] {
        &self.data
    }

    /// The pixel at column `x`, row `y` (from the top), or `None` outside the image.
    #[must_use]
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = 4 * (y as usize * self.width as usize + x as usize);
        Some([self.data[i], self.data[i + 1], self.data[i + 2], self.data[i + 3]])
    }

    /// Iterates over the pixels, row by row.
    pub fn iter_pixels(&self) -> impl ExactSizeIterator<Item = [u8; 4]> + '_ {
        self.data.chunks_exact(4).map(|p| [p[0], p[1], p[2], p[3]])
    }

    /// The PNG encoding (8-bit RGBA). The same image always gives the same bytes.
    ///
    /// # Errors
    /// [`RenderError::Png`] if the encoder fails (it does not for images of a valid size).
    pub fn encode_png(&self) -> Result<Vec<u8>, RenderError> {
        self.to_pixmap()?.encode_png().map_err(|e| RenderError::Png(e.to_string()))
    }

    /// Decodes a PNG (any colour type the decoder knows; alpha is kept as stored).
    ///
    /// # Errors
    /// [`RenderError::Png`] if the bytes are not a PNG.
    pub fn decode_png(bytes: &[u8]) -> Result<Self, RenderError> {
        let pixmap = tiny_skia::Pixmap::decode_png(bytes).map_err(|e| RenderError::Png(e.to_string()))?;
        Ok(Self::from_pixmap(&pixmap))
    }

    /// Writes the image as a PNG file: to a temporary file in the same directory, renamed into
    /// place, so that a failure never leaves a partial file.
    ///
    /// # Errors
    /// [`RenderError::Png`] from the encoder, or [`RenderError::Write`] naming the path.
    pub fn write_png(&self, path: impl AsRef<Path>) -> Result<(), RenderError> {
        let bytes = self.encode_png()?;
        write_bytes(path.as_ref(), &bytes)
    }

    /// Fills the `w × h` rectangle with its top left corner at `(x, y)` with an opaque
    /// colour; the part outside the image is cut off.
    pub(crate) fn fill_rect(&mut self, x: i64, y: i64, w: u32, h: u32, colour: Rgb) {
        let (iw, ih) = (i64::from(self.width), i64::from(self.height));
        let (x0, x1) = (x.clamp(0, iw), (x + i64::from(w)).clamp(0, iw));
        let (y0, y1) = (y.clamp(0, ih), (y + i64::from(h)).clamp(0, ih));
        let [r, g, b] = colour;
        for row in y0..y1 {
            let start = 4 * (row * iw + x0) as usize;
            let end = 4 * (row * iw + x1) as usize;
            for p in self.data[start..end].chunks_exact_mut(4) {
                p.copy_from_slice(&[r, g, b, 255]);
            }
        }
    }

    /// The image as a tiny-skia pixmap (premultiplied; the same bytes for opaque images).
    pub(crate) fn to_pixmap(&self) -> Result<tiny_skia::Pixmap, RenderError> {
        let size = tiny_skia::IntSize::from_wh(self.width, self.height)
            .ok_or_else(|| RenderError::Png(format!("cannot encode a {}x{} image", self.width, self.height)))?;
        let premultiplied: Vec<u8> = self
            .data
            .chunks_exact(4)
            .flat_map(|p| {
                let a = u16::from(p[3]);
                let m = |c: u8| ((u16::from(c) * a + 127) / 255) as u8;
                [m(p[0]), m(p[1]), m(p[2]), p[3]]
            })
            .collect();
        tiny_skia::Pixmap::from_vec(premultiplied, size)
            .ok_or_else(|| RenderError::Png(format!("cannot encode a {}x{} image", self.width, self.height)))
    }

    /// An image from a tiny-skia pixmap (demultiplied).
    pub(crate) fn from_pixmap(pixmap: &tiny_skia::Pixmap) -> Self {
        let data = pixmap
            .pixels()
            .iter()
            .flat_map(|p| {
                let c = p.demultiply();
                [c.red(), c.green(), c.blue(), c.alpha()]
            })
            .collect();
        Self { width: pixmap.width(), height: pixmap.height(), data }
    }
}

/// Writes `bytes` to `path` through a temporary file and a rename.
pub(crate) fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), RenderError> {
    splinekit_io::atomic::write_file(path, |w| {
        std::io::Write::write_all(w, bytes)
            .map_err(|error| RenderError::Write { path: path.display().to_string(), error })
    })
}

/// The size of a picture in pixels, parsed from `WxH` (for example `800x600`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ImageSize {
    /// Width, 1..=[`MAX_SIDE`].
    pub width: u32,
    /// Height, 1..=[`MAX_SIDE`].
    pub height: u32,
}

impl ImageSize {
    /// The default size, 800×600.
    pub const DEFAULT: Self = Self { width: 800, height: 600 };

    /// A size, or `None` if a side is 0 or larger than [`MAX_SIDE`].
    #[must_use]
    pub fn new(width: u32, height: u32) -> Option<Self> {
        let ok = |s: u32| (1..=MAX_SIDE).contains(&s);
        (ok(width) && ok(height)).then_some(Self { width, height })
    }

    /// `width × height`.
    #[must_use]
    pub fn num_pixels(self) -> usize {
        self.width as usize * self.height as usize
    }

    /// `width / height`.
    #[must_use]
    pub fn aspect(self) -> f64 {
        f64::from(self.width) / f64::from(self.height)
    }
}

impl Default for ImageSize {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl fmt::Display for ImageSize {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}x{}", self.width, self.height)
    }
}

/// Why a `WxH` size did not parse.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SizeError {
    /// Not of the form `WxH`.
    #[error("expected WIDTHxHEIGHT such as 800x600, found {0:?}")]
    Syntax(String),
    /// A side is 0 or too large.
    #[error("{side} must be from 1 to {MAX_SIDE} pixels, found {value}")]
    OutOfRange {
        /// `width` or `height`.
        side: &'static str,
        /// The number given.
        value: String,
    },
}

impl FromStr for ImageSize {
    type Err = SizeError;

    /// Parses `WxH` (`x`, `X` or `×` between two decimal numbers, no spaces).
    fn from_str(s: &str) -> Result<Self, SizeError> {
        let syntax = || SizeError::Syntax(s.to_string());
        let (w, h) = s.split_once(['x', 'X', '×']).ok_or_else(syntax)?;
        let side = |text: &str, name: &'static str| -> Result<u32, SizeError> {
            if text.is_empty() || !text.bytes().all(|b| b.is_ascii_digit()) {
                return Err(syntax());
            }
            let range = || SizeError::OutOfRange { side: name, value: text.to_string() };
            let value: u32 = text.parse().map_err(|_| range())?;
            if (1..=MAX_SIDE).contains(&value) { Ok(value) } else { Err(range()) }
        };
        Ok(Self { width: side(w, "width")?, height: side(h, "height")? })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse() {
        assert_eq!("800x600".parse(), Ok(ImageSize { width: 800, height: 600 }));
        assert_eq!("1X2".parse(), Ok(ImageSize { width: 1, height: 2 }));
        assert_eq!("8×9".parse(), Ok(ImageSize { width: 8, height: 9 }));
        assert!(matches!("abc".parse::<ImageSize>(), Err(SizeError::Syntax(_))));
        assert!(matches!("800x".parse::<ImageSize>(), Err(SizeError::Syntax(_))));
        assert!(matches!("-1x5".parse::<ImageSize>(), Err(SizeError::Syntax(_))));
        assert!(matches!("8 x 9".parse::<ImageSize>(), Err(SizeError::Syntax(_))));
        let err = "0x5".parse::<ImageSize>().unwrap_err();
        assert_eq!(err.to_string(), "width must be from 1 to 8192 pixels, found 0");
        let err = "5x99999999999".parse::<ImageSize>().unwrap_err();
        assert_eq!(err.to_string(), "height must be from 1 to 8192 pixels, found 99999999999");
    }

    #[test]
    fn png_round_trips() {
        let mut image = Image::filled(ImageSize::new(3, 2).unwrap(), [10, 20, 30]);
        image.data[4..8].copy_from_slice(&[200, 100, 0, 255]);
        let png = image.encode_png().unwrap();
        assert_eq!(&png[1..4], b"PNG");
        assert_eq!(Image::decode_png(&png).unwrap(), image);
        assert_eq!(image.pixel(1, 0), Some([200, 100, 0, 255]));
        assert_eq!(image.pixel(3, 0), None);
    }
}
