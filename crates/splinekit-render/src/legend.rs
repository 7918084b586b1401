//! [`Legend`]: what the colours of a curvature or level picture stand for, drawn into the
//! picture's bottom left corner with the built-in bitmap font.
//!
//! - Curvature: the name (`mean curvature`, `Gaussian curvature`) over a colour bar of
//!   [`diverging_colour`] from `−m` to `+m`, with the values `−m`, `0` and `+m` under its
//!   ends and middle (three significant digits, e.g. `-2.50e-1`). An end of the bar is
//!   pointed when some values lie beyond it (they show its colour).
//! - Level: a swatch of each level's colour with `level 0`, `level 1`, … beside it.
//!
//! The legend sits on a dark panel so that it stays readable over a surface, and its size
//! follows the picture's: font pixels of `⌊min(width, height)/240⌋` image pixels (1 to 4).
//! A legend that does not fit the picture at the smallest size is left out.

use crate::colour::{Curvature, diverging_colour, level_colour};
use crate::font::{GLYPH_HEIGHT, draw_text, text_width};
use crate::image::{Image, Rgb};

/// The legend's panel.
pub const LEGEND_PANEL: Rgb = [24, 26, 31];
/// The legend's text.
pub const LEGEND_TEXT: Rgb = [232, 232, 232];

/// Font pixels per side of the colour bar's length.
const BAR_LENGTH: u32 = 128;
/// Font pixels of the colour bar's height.
const BAR_HEIGHT: u32 = 8;
/// Font pixels of the colour bar's pointed ends.
const POINT: u32 = 5;

/// What the colours of a picture stand for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Legend {
    /// A curvature on the diverging map from `−scale` (blue) through 0 (light grey) to
    /// `+scale` (crimson); values beyond show the end colours.
    Curvature {
        /// Which curvature.
        curvature: Curvature,
        /// The half-width `m` of the scale `[−m, m]`.
        scale: f64,
        /// The smallest value shown (0 if none).
        min: f64,
        /// The largest value shown (0 if none).
        max: f64,
    },
    /// Subdivision levels `0..=levels`, each in its [`level_colour`].
    Levels {
        /// The finest level.
        levels: u32,
    },
}

impl Legend {
    /// One line for messages: `mean curvature from -2.50e-1 to +2.50e-1`, or `levels 0 to 2`.
    #[must_use]
    pub fn describe(&self) -> String {
        match *self {
            Self::Curvature { curvature, scale, .. } => {
                format!("{} from {} to {}", curvature.title(), format_value(-scale), format_value(scale))
            }
            Self::Levels { levels: 0 } => String::from("level 0"),
            Self::Levels { levels } => format!("levels 0 to {levels}"),
        }
    }

    /// Draws the legend into the bottom left corner of `image` (see the [module docs](self)).
    /// Returns whether it fitted (a picture too small for it is left as it is).
    pub fn draw(&self, image: &mut Image) -> bool {
        let side = image.width().min(image.height());
        let largest = (side / 240).clamp(1, 4);
        for s in (1..=largest).rev() {
            let (w, h) = self.panel_size(s);
            let margin = 6 * s;
            if w + 2 * margin <= image.width() && h + 2 * margin <= image.height() {
                let (x, y) = (i64::from(margin), i64::from(image.height() - margin - h));
                image.fill_rect(x, y, w, h, LEGEND_PANEL);
                self.draw_contents(image, x + i64::from(pad(s)), y + i64::from(pad(s)), s);
                return true;
            }
        }
        false
    }

    /// The panel's width and height at font scale `s`.
    fn panel_size(&self, s: u32) -> (u32, u32) {
        let th = GLYPH_HEIGHT * s;
        let (w, h) = match *self {
            Self::Curvature { curvature, scale, .. } => {
                let labels = [format_value(-scale), String::from("0"), format_value(scale)];
                let row: u32 = labels.iter().map(|l| text_width(l, s)).sum::<u32>() + 2 * gap(s);
                let w = text_width(curvature.title(), s).max((BAR_LENGTH + 2 * POINT) * s).max(row);
                (w, th + gap(s) + BAR_HEIGHT * s + tick(s) + gap(s) + th)
            }
            Self::Levels { levels } => {
                let rows = levels + 1;
                let w = th + gap(s) + text_width(&format!("level {levels}"), s);
                (w, rows * th + (rows - 1) * gap(s))
            }
        };
        (w + 2 * pad(s), h + 2 * pad(s))
    }

    /// The contents, their top left corner at `(x, y)`.
    fn draw_contents(&self, image: &mut Image, x: i64, y: i64, s: u32) {
        let th = i64::from(GLYPH_HEIGHT * s);
        let si = i64::from(s);
        match *self {
            Self::Curvature { curvature, scale, min, max } => {
                draw_text(image, x, y, s, curvature.title(), LEGEND_TEXT);
                let bar_y = y + th + i64::from(gap(s));
                let (len, height) = (BAR_LENGTH * s, BAR_HEIGHT * s);
                let x = x + i64::from(POINT * s);
                for i in 0..len {
                    let t = (2.0 * f64::from(i) + 1.0) / f64::from(len) - 1.0;
                    image.fill_rect(x + i64::from(i), bar_y, 1, height, diverging_colour(t));
                }
                // Pointed ends where values lie beyond the scale: columns narrowing outwards.
                let point = POINT * s;
                for (beyond, end, t) in [(min < -scale, x - 1, -1.0), (max > scale, x + i64::from(len), 1.0)] {
                    if !beyond {
                        continue;
                    }
                    for k in 0..point {
                        let h = height * (point - k) / (point + 1);
                        let column = if t < 0.0 { end - i64::from(k) } else { end + i64::from(k) };
                        image.fill_rect(column, bar_y + i64::from((height - h) / 2), 1, h, diverging_colour(t));
                    }
                }
                // Ticks under the ends and the middle, and the values under them.
                let tick_y = bar_y + i64::from(height);
                let centre = x + i64::from(len / 2);
                for tx in [x, centre - si / 2, x + i64::from(len) - si] {
                    image.fill_rect(tx, tick_y, s, tick(s), LEGEND_TEXT);
                }
                let label_y = tick_y + i64::from(tick(s) + gap(s));
                let (lo, hi) = (format_value(-scale), format_value(scale));
                draw_text(image, x, label_y, s, &lo, LEGEND_TEXT);
                draw_text(image, centre - i64::from(text_width("0", s) / 2), label_y, s, "0", LEGEND_TEXT);
                draw_text(image, x + i64::from(len) - i64::from(text_width(&hi, s)), label_y, s, &hi, LEGEND_TEXT);
            }
            Self::Levels { levels } => {
                for level in 0..=levels {
                    let row_y = y + i64::from(level) * (th + i64::from(gap(s)));
                    image.fill_rect(x, row_y, GLYPH_HEIGHT * s, GLYPH_HEIGHT * s, level_colour(level));
                    let text_x = x + th + i64::from(gap(s));
                    draw_text(image, text_x, row_y, s, &format!("level {level}"), LEGEND_TEXT);
                }
            }
        }
    }
}

/// A value of a legend: three significant digits with its sign, `-2.50e-1`, `+1.25e0`
/// (`0` for zero).
#[must_use]
pub fn format_value(v: f64) -> String {
    if v == 0.0 { String::from("0") } else { format!("{v:+.2e}") }
}

/// The panel's inner margin.
fn pad(s: u32) -> u32 {
    5 * s
}

/// The space between rows and between labels.
fn gap(s: u32) -> u32 {
    3 * s
}

/// The length of a tick under the colour bar.
fn tick(s: u32) -> u32 {
    3 * s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ImageSize;
    use crate::colour::DIVERGING_STOPS;

    #[test]
    fn values_and_descriptions() {
        assert_eq!(format_value(-0.25), "-2.50e-1");
        assert_eq!(format_value(1234.5), "+1.23e3");
        assert_eq!(format_value(0.0), "0");
        let mean = Legend::Curvature { curvature: Curvature::Mean, scale: 0.5, min: -0.1, max: 0.9 };
        assert_eq!(mean.describe(), "mean curvature from -5.00e-1 to +5.00e-1");
        assert_eq!(Legend::Levels { levels: 2 }.describe(), "levels 0 to 2");
    }

    #[test]
    fn colour_bar_runs_from_blue_to_crimson() {
        let bg = [44, 47, 54];
        let mut image = Image::filled(ImageSize::new(640, 480).unwrap(), bg);
        let legend = Legend::Curvature { curvature: Curvature::Gaussian, scale: 2.0, min: -2.0, max: 3.0 };
        assert!(legend.draw(&mut image));
        // Scale 2: the panel at (12, 480 − 12 − h), the bar 5·2 in from its left and its top
        // after the pointed end (10), the title (14) and a gap (6).
        let (w, h) = legend.panel_size(2);
        let (x, y) = (12 + 10 + 10, 480 - 12 - h + 10 + 14 + 6);
        let at = |px: u32| {
            let p = image.pixel(px, y + 4).unwrap();
            [p[0], p[1], p[2]]
        };
        assert_eq!(at(x), diverging_colour(-1.0 + 1.0 / 256.0));
        assert_eq!(at(x + 255), diverging_colour(1.0 - 1.0 / 256.0));
        let mid = at(x + 128);
        assert!(mid.iter().zip(DIVERGING_STOPS[2]).all(|(a, b)| a.abs_diff(b) <= 2), "{mid:?}");
        // Values beyond +2 only: the right end is pointed, the left is not.
        let panel = [LEGEND_PANEL[0], LEGEND_PANEL[1], LEGEND_PANEL[2]];
        assert_eq!(at(x + 256), DIVERGING_STOPS[4]);
        assert_eq!(at(x - 1), panel);
        assert_eq!(image.pixel(12 + w, 479 - 12), Some([bg[0], bg[1], bg[2], 255]), "nothing beyond the panel");
        // The same bytes each time.
        let mut again = Image::filled(ImageSize::new(640, 480).unwrap(), bg);
        legend.draw(&mut again);
        assert!(again == image);
    }

    #[test]
    fn level_swatches_and_small_pictures() {
        let mut image = Image::filled(ImageSize::new(200, 150).unwrap(), [0, 0, 0]);
        assert!(Legend::Levels { levels: 3 }.draw(&mut image));
        // Scale 1: swatch k at (6 + 5, 150 − 6 − h + 5 + 10k).
        let (_, h) = Legend::Levels { levels: 3 }.panel_size(1);
        for k in 0..=3u32 {
            let p = image.pixel(11 + 3, 150 - 6 - h + 5 + 10 * k + 3).unwrap();
            assert_eq!([p[0], p[1], p[2]], level_colour(k), "level {k}");
        }
        let mut tiny = Image::filled(ImageSize::new(40, 30).unwrap(), [0, 0, 0]);
        assert!(!Legend::Curvature { curvature: Curvature::Mean, scale: 1.0, min: 0.0, max: 0.0 }.draw(&mut tiny));
        assert!(tiny.iter_pixels().all(|p| p == [0, 0, 0, 255]));
    }
}
