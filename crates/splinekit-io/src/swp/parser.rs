//! The SWP parser: tokens to [`SwpDocument`].

use std::collections::HashMap;

use glam::DVec3;
use splinekit::{MAX_BEZIER_POINTS, MAX_NURBS_DEGREE, MAX_NURBS_POINTS, Tcb};

use super::error::{SwpError, SwpErrorKind};
use super::lexer::{Token, TokenKind, tokenize};
use super::validate::SwpCurveRole;
use splinekit::sweep::{Join, MeshLayout};

use crate::surface::{ProfileAlign, ScaleMode};

use super::{
    DEFAULT_NURBS_DEGREE, DEFAULT_XSWEEP_EPSILON, DEFAULT_ZREV_EPSILON, DEFAULT_ZREV_SLICE_TOLERANCE, MAX_HELIX_TURNS,
    MAX_STEPS, SETTING_WORDS, SourcePos, SwpClause, SwpCurve, SwpCurveKind, SwpDocument, SwpFrames, SwpGeometry,
    SwpSurface, SwpSurfaceKind, SwpSurfaceSettings, SwpTessellation,
};

/// Every keyword that starts an object.
const KEYWORDS: [&str; 24] = [
    "bez2", "bsp2", "bez3", "bsp3", "cr2", "cr3", "her2", "her3", "tcb2", "tcb3", "bo2", "bo3", "bezn2", "bezn3",
    "nurbs2", "nurbs3", "circ", "helix", "trefoil", "srev", "gcyl", "zrev", "xsweep", "lathe",
];

/// Whether `word` is an SWP keyword.
pub(crate) fn is_keyword(word: &str) -> bool {
    KEYWORDS.contains(&word)
}

/// The spline families that have control points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Family {
    Bezier,
    BSpline,
    CatmullRom,
    Hermite,
    KochanekBartels,
    BesselOverhauser,
    BezierN,
    Nurbs,
}

/// What a keyword starts.
#[derive(Debug, Clone, Copy)]
enum Keyword {
    Curve { keyword: &'static str, family: Family, dim: u8 },
    Circle,
    Helix,
    Trefoil,
    Revolution,
    Cylinder,
    RevolutionZ,
    ToolSweep,
    Lathe,
}

fn keyword(word: &str) -> Option<Keyword> {
    let curve = |keyword, family, dim| Some(Keyword::Curve { keyword, family, dim });
    match word {
        "bez2" => curve("bez2", Family::Bezier, 2),
        "bez3" => curve("bez3", Family::Bezier, 3),
        "bsp2" => curve("bsp2", Family::BSpline, 2),
        "bsp3" => curve("bsp3", Family::BSpline, 3),
        "cr2" => curve("cr2", Family::CatmullRom, 2),
        "cr3" => curve("cr3", Family::CatmullRom, 3),
        "her2" => curve("her2", Family::Hermite, 2),
        "her3" => curve("her3", Family::Hermite, 3),
        "tcb2" => curve("tcb2", Family::KochanekBartels, 2),
        "tcb3" => curve("tcb3", Family::KochanekBartels, 3),
        "bo2" => curve("bo2", Family::BesselOverhauser, 2),
        "bo3" => curve("bo3", Family::BesselOverhauser, 3),
        "bezn2" => curve("bezn2", Family::BezierN, 2),
        "bezn3" => curve("bezn3", Family::BezierN, 3),
        "nurbs2" => curve("nurbs2", Family::Nurbs, 2),
        "nurbs3" => curve("nurbs3", Family::Nurbs, 3),
        "circ" => Some(Keyword::Circle),
        "helix" => Some(Keyword::Helix),
        "trefoil" => Some(Keyword::Trefoil),
        "srev" => Some(Keyword::Revolution),
        "gcyl" => Some(Keyword::Cylinder),
        "zrev" => Some(Keyword::RevolutionZ),
        "xsweep" => Some(Keyword::ToolSweep),
        "lathe" => Some(Keyword::Lathe),
        _ => None,
    }
}

impl Family {
    /// The curve kind of this family; `alpha` is the Catmull-Rom parametrization, `degree` the
    /// NURBS degree.
    fn kind(self, alpha: f64, degree: u32) -> SwpCurveKind {
        match self {
            Self::Bezier => SwpCurveKind::Bezier,
            Self::BSpline => SwpCurveKind::BSpline,
            Self::CatmullRom => SwpCurveKind::CatmullRom { alpha },
            Self::Hermite => SwpCurveKind::Hermite,
            Self::KochanekBartels => SwpCurveKind::KochanekBartels,
            Self::BesselOverhauser => SwpCurveKind::BesselOverhauser,
            Self::BezierN => SwpCurveKind::BezierN,
            Self::Nurbs => SwpCurveKind::Nurbs { degree },
        }
    }
}

/// Parses an integer: an optional sign and ASCII digits. Huge magnitudes saturate at
/// `u64::MAX`, so the caller can still report "out of range" rather than "not an integer".
fn int_value(text: &str) -> Option<i128> {
    let (negative, digits) = match text.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, text.strip_prefix('+').unwrap_or(text)),
    };
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let magnitude = digits.bytes().fold(0u64, |acc, b| acc.saturating_mul(10).saturating_add(u64::from(b - b'0')));
    let value = i128::from(magnitude);
    Some(if negative { -value } else { value })
}

/// Parses a finite decimal number (`nan`, `inf` and overflowing numbers are rejected).
fn number(text: &str) -> Option<f64> {
    text.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// `bez2 curve "profile"` or `bez2 curve #0`.
fn label(keyword: &str, noun: &str, name: Option<&str>, index: usize) -> String {
    match name {
        Some(name) => format!("{keyword} {noun} {name:?}"),
        None => format!("{keyword} {noun} #{index}"),
    }
}

/// The first token of each group of surface settings read so far (tessellation, layout,
/// frames, caps).
type Seen<'a> = [Option<Token<'a>>; 8];

/// What a name refers to.
#[derive(Debug, Clone, Copy)]
enum Named {
    Curve(usize),
    Surface(usize),
}

/// Parses SWP text; see [`SwpDocument::parse`].
pub(crate) fn parse(text: &str, origin: &str) -> Result<SwpDocument, SwpError> {
    let mut parser =
        Parser { tokens: tokenize(text), next: 0, origin, doc: SwpDocument::default(), names: HashMap::new() };
    while let Some(token) = parser.bump() {
        parser.object(token)?;
    }
    Ok(parser.doc)
}

struct Parser<'a> {
    tokens: Vec<Token<'a>>,
    next: usize,
    origin: &'a str,
    doc: SwpDocument,
    /// Every name defined so far, with what it names and where the name token stood.
    names: HashMap<&'a str, (Named, SourcePos)>,
}

impl<'a> Parser<'a> {
    fn peek(&self) -> Option<Token<'a>> {
        self.tokens.get(self.next).copied()
    }

    fn bump(&mut self) -> Option<Token<'a>> {
        let token = self.peek();
        if token.is_some() {
            self.next += 1;
        }
        token
    }

    /// How many tokens are left.
    fn remaining(&self) -> usize {
        self.tokens.len().saturating_sub(self.next)
    }

    /// Where "end of file" errors point: just after the last token.
    fn end_pos(&self) -> SourcePos {
        self.tokens.last().map_or_else(SourcePos::default, |t| t.end)
    }

    fn error(&self, pos: SourcePos, kind: SwpErrorKind) -> SwpError {
        SwpError::at(self.origin, pos, kind)
    }

    fn unexpected(&self, token: Token<'_>, expected: String) -> SwpError {
        self.error(token.pos, SwpErrorKind::UnexpectedToken { found: token.text.to_owned(), expected })
    }

    fn invalid_number(&self, token: Token<'_>, expected: String) -> SwpError {
        self.error(token.pos, SwpErrorKind::InvalidNumber { found: token.text.to_owned(), expected })
    }

    fn bad_option(&self, token: Token<'_>, expected: String) -> SwpError {
        self.error(token.pos, SwpErrorKind::BadOption { found: token.text.to_owned(), expected })
    }

    /// The next token, or an "unexpected end of file" error expecting `expected()`.
    fn expect(&mut self, expected: impl FnOnce() -> String) -> Result<Token<'a>, SwpError> {
        match self.bump() {
            Some(token) => Ok(token),
            None => Err(self.error(self.end_pos(), SwpErrorKind::UnexpectedEnd { expected: expected() })),
        }
    }

    fn object(&mut self, token: Token<'a>) -> Result<(), SwpError> {
        let keyword = match token.kind {
            TokenKind::Word => keyword(token.text),
            TokenKind::Open | TokenKind::Close => None,
        };
        match keyword {
            None => Err(self.error(token.pos, SwpErrorKind::UnknownKeyword { found: token.text.to_owned() })),
            Some(Keyword::Curve { keyword, family, dim }) => self.curve(token.pos, keyword, family, dim),
            Some(Keyword::Circle) => self.circle(token.pos),
            Some(Keyword::Helix) => self.helix(token.pos),
            Some(Keyword::Trefoil) => self.trefoil(token.pos),
            Some(Keyword::Revolution) => self.revolution(token.pos),
            Some(Keyword::Cylinder) => self.cylinder(token.pos),
            Some(Keyword::RevolutionZ) => self.revolution_z(token.pos),
            Some(Keyword::ToolSweep) => self.tool_sweep(token.pos),
            Some(Keyword::Lathe) => self.lathe(token.pos),
        }
    }

    /// Reads NAME: `None` for `.`. `what` is like `bez2 curve`.
    fn name(&mut self, what: &str) -> Result<(Option<&'a str>, SourcePos), SwpError> {
        let expected = || format!("a name or `.` for the {what}");
        let token = self.expect(expected)?;
        if token.kind != TokenKind::Word {
            return Err(self.unexpected(token, expected()));
        }
        if token.text == "." {
            return Ok((None, token.pos));
        }
        if let Some(&(named, first)) = self.names.get(token.text) {
            let what = match named {
                Named::Curve(i) => self.doc.curves.get(i).map_or("curve", |c| c.keyword()),
                Named::Surface(i) => self.doc.surfaces.get(i).map_or("surface", |s| s.kind.keyword()),
            };
            let noun = match named {
                Named::Curve(_) => "curve",
                Named::Surface(_) => "surface",
            };
            return Err(self.error(
                token.pos,
                SwpErrorKind::DuplicateName { name: token.text.to_owned(), what: format!("{what} {noun}"), first },
            ));
        }
        Ok((Some(token.text), token.pos))
    }

    fn register(&mut self, name: Option<&'a str>, pos: SourcePos, named: Named) {
        if let Some(name) = name {
            self.names.insert(name, (named, pos));
        }
    }

    /// Reads STEPS for the object `label`.
    fn steps(&mut self, label: &str) -> Result<u32, SwpError> {
        let expected = || format!("a step count (an integer from 1 to {MAX_STEPS}) for {label}");
        let token = self.expect(expected)?;
        match int_value(token.text) {
            None => Err(self.invalid_number(token, expected())),
            Some(value) => u32::try_from(value).ok().filter(|steps| (1..=MAX_STEPS).contains(steps)).ok_or_else(|| {
                self.error(
                    token.pos,
                    SwpErrorKind::StepsOutOfRange { found: token.text.to_owned(), object: label.to_owned() },
                )
            }),
        }
    }

    /// `bez2 … bsp3 cr2 cr3 her2 her3 tcb2 tcb3 bo2 bo3 bezn2 bezn3 nurbs2 nurbs3`, after the
    /// keyword.
    fn curve(&mut self, pos: SourcePos, keyword: &'static str, family: Family, dim: u8) -> Result<(), SwpError> {
        let index = self.doc.curves.len();
        let (name, name_pos) = self.name(&format!("{keyword} curve"))?;
        let label = label(keyword, "curve", name, index);
        let steps = self.steps(&label)?;

        let pairs = family == Family::Hermite;
        // Kochanek–Bartels keys carry their tension, continuity and bias after the coordinates,
        // NURBS points their weight
        let extra = match family {
            Family::KochanekBartels => Extra::Shape,
            Family::Nurbs => Extra::Weight,
            _ => Extra::None,
        };
        let items = if pairs { "point pairs" } else { "points" };
        let expected = || format!("the number of {items} (an integer ≥ 0) of {label}");
        let count_token = self.expect(expected)?;
        let count = match int_value(count_token.text) {
            Some(value) if value >= 0 => u64::try_from(value).unwrap_or(u64::MAX),
            _ => return Err(self.invalid_number(count_token, expected())),
        };
        let header = Header { keyword, family, label: &label, count, count_token };

        let options = self.options(&header)?;
        let kind = family.kind(options.alpha, options.degree);
        self.check_count(&header, kind, options.closed)?;

        // Each point takes at least `dim + 2` tokens, so the remaining tokens bound how many
        // points can follow: never reserve memory for a count the input cannot back.
        let tokens_per_item = (usize::from(dim + 2) + extra.names().len()) * if pairs { 2 } else { 1 };
        let capacity = usize::try_from(count).unwrap_or(usize::MAX).min(self.remaining() / tokens_per_item);
        let with_extra = |extra_kind: Extra| if extra == extra_kind { capacity } else { 0 };
        let mut points = Vec::with_capacity(capacity);
        let mut tangents = Vec::with_capacity(if pairs { capacity } else { 0 });
        let mut shape = Vec::with_capacity(with_extra(Extra::Shape));
        let mut weights = Vec::with_capacity(with_extra(Extra::Weight));
        for i in 0..count {
            let n = i + 1;
            match self.peek() {
                None => {
                    return Err(self.error(
                        self.end_pos(),
                        SwpErrorKind::MissingPoints { curve: label, expected: count, found: i, pairs },
                    ));
                }
                Some(token) if i == 0 && token.kind == TokenKind::Word => {
                    return Err(self.bad_option(
                        token,
                        format!("`[` starting point 1 of {label}, or a curve option ({})", option_list(family)),
                    ));
                }
                Some(_) => {}
            }
            let (point, values) = self.bracketed(dim, extra, "point", n, count, &label)?;
            points.push(point);
            match extra {
                Extra::Shape => shape.push(Tcb::new(values[0], values[1], values[2])),
                Extra::Weight => weights.push(values[0]),
                Extra::None => {}
            }
            if pairs {
                tangents.push(self.point(dim, "tangent", n, count, &label)?);
            }
        }

        let geometry = match extra {
            Extra::Shape => SwpGeometry::Tcb { points, shape },
            Extra::Weight => SwpGeometry::Nurbs { points, weights, knots: options.knots },
            Extra::None if pairs => SwpGeometry::Hermite { points, tangents },
            Extra::None => SwpGeometry::Points(points),
        };
        self.register(name, name_pos, Named::Curve(index));
        self.doc.curves.push(SwpCurve {
            name: name.map(str::to_owned),
            kind,
            dim,
            steps,
            closed: options.closed,
            geometry,
            pos,
        });
        Ok(())
    }

    /// Checks NPOINTS against the point-count rule of `kind`, closed or open.
    fn check_count(&self, header: &Header<'_, '_>, kind: SwpCurveKind, closed: bool) -> Result<(), SwpError> {
        let Header { keyword, label, count, count_token, .. } = *header;
        if kind.accepts_point_count(closed, count) {
            return Ok(());
        }
        let rule = match kind {
            SwpCurveKind::BezierN => {
                format!("2 to {MAX_BEZIER_POINTS} points (one Bézier curve of degree NPOINTS − 1)")
            }
            SwpCurveKind::Nurbs { degree } => {
                let least = (u64::from(degree) + 1).max(if closed { 3 } else { 2 });
                let closed = if closed { ", and 3 for a closed curve" } else { "" };
                let hint = if degree == DEFAULT_NURBS_DEGREE { "; `degree D` sets another degree" } else { "" };
                format!("at least {least} points (degree {degree} + 1{closed}{hint}) and at most {MAX_NURBS_POINTS}")
            }
            _ => {
                return Err(self.error(
                    count_token.pos,
                    SwpErrorKind::PointCount { curve: label.to_owned(), keyword, closed, found: count },
                ));
            }
        };
        Err(self.error(count_token.pos, SwpErrorKind::PointRange { curve: label.to_owned(), rule, found: count }))
    }

    /// Reads the option words between NPOINTS and the first `[`. Stops at the first token that
    /// is not an option word and leaves it.
    fn options(&mut self, header: &Header<'a, '_>) -> Result<CurveOptions, SwpError> {
        let Header { keyword, family, label, .. } = *header;
        let mut closed: Option<Token<'a>> = None;
        let mut alpha: Option<(Token<'a>, f64)> = None;
        let mut degree: Option<(Token<'a>, u32)> = None;
        let mut knots: Option<(Token<'a>, Vec<f64>)> = None;
        while let Some(token) = self.peek() {
            // `[knots k0 … kM]`: the knot vector in brackets
            let bracketed_knots =
                token.kind == TokenKind::Open && self.tokens.get(self.next + 1).is_some_and(|t| t.text == "knots");
            let word = match token.text {
                "closed" | "open" => OptionWord::Openness,
                "uniform" => OptionWord::Alpha(Some(0.0)),
                "centripetal" => OptionWord::Alpha(Some(0.5)),
                "chordal" => OptionWord::Alpha(Some(1.0)),
                "alpha" => OptionWord::Alpha(None),
                "degree" => OptionWord::Degree,
                "knots" => OptionWord::Knots,
                _ if bracketed_knots => OptionWord::Knots,
                _ => break,
            };
            self.next += 1;
            let (owner, owners) = match word {
                OptionWord::Openness => (family, ""),
                OptionWord::Alpha(_) => (Family::CatmullRom, "cr2 and cr3"),
                OptionWord::Degree | OptionWord::Knots => (Family::Nurbs, "nurbs2 and nurbs3"),
            };
            if owner != family {
                let word = if bracketed_knots { "knots" } else { token.text };
                return Err(self.bad_option(
                    token,
                    format!("a curve option of {label} ({}); `{word}` applies to {owners} only", option_list(family)),
                ));
            }
            match word {
                OptionWord::Openness => {
                    if let Some(first) = closed {
                        return Err(self.bad_option(token, already(label, first, "closed or open")));
                    }
                    if token.text == "closed" && family == Family::BezierN {
                        return Err(self.bad_option(
                            token,
                            format!(
                                "`open` or `[` starting point 1 of {label}: a {keyword} curve is one open Bézier \
                                 curve (repeat its first point at the end to close it)"
                            ),
                        ));
                    }
                    if token.text == "closed"
                        && let Some((first, _)) = &knots
                    {
                        return Err(self.bad_option(token, periodic_with_knots(label, *first)));
                    }
                    closed = Some(token);
                }
                OptionWord::Alpha(named_value) => {
                    if let Some((first, _)) = alpha {
                        return Err(self.bad_option(token, already(label, first, "a parametrization")));
                    }
                    let value = match named_value {
                        Some(value) => value,
                        None => {
                            let expected = || format!("the alpha value (a number from 0 to 1) of {label}");
                            let value_token = self.expect(expected)?;
                            let value =
                                number(value_token.text).ok_or_else(|| self.invalid_number(value_token, expected()))?;
                            if !(0.0..=1.0).contains(&value) {
                                return Err(
                                    self.bad_option(value_token, format!("an alpha value from 0 to 1 for {label}"))
                                );
                            }
                            value
                        }
                    };
                    alpha = Some((token, value));
                }
                OptionWord::Degree => {
                    if let Some((first, _)) = degree {
                        return Err(self.bad_option(token, already(label, first, "degree")));
                    }
                    if let Some((first, _)) = &knots {
                        return Err(self.bad_option(
                            token,
                            format!(
                                "`[` starting point 1 of {label}: `degree` must come before `knots` (at line {}, \
                                 column {}), as the number of knots depends on it",
                                first.pos.line, first.pos.column
                            ),
                        ));
                    }
                    let expected = || format!("a degree (an integer from 1 to {MAX_NURBS_DEGREE}) for {label}");
                    let value_token = self.expect(expected)?;
                    let value = int_value(value_token.text)
                        .and_then(|d| u32::try_from(d).ok())
                        .filter(|d| (1..=MAX_NURBS_DEGREE as u32).contains(d))
                        .ok_or_else(|| self.invalid_number(value_token, expected()))?;
                    degree = Some((token, value));
                }
                OptionWord::Knots => {
                    if let Some((first, _)) = &knots {
                        return Err(self.bad_option(token, already(label, *first, "knots")));
                    }
                    if let Some(first) = closed.filter(|t| t.text == "closed") {
                        return Err(self.bad_option(token, periodic_with_knots(label, first)));
                    }
                    if bracketed_knots {
                        self.next += 1; // the word `knots` after `[`
                    }
                    let d = degree.map_or(DEFAULT_NURBS_DEGREE, |(_, d)| d);
                    let values = self.knots(header, d, bracketed_knots)?;
                    knots = Some((token, values));
                }
            }
        }
        Ok(CurveOptions {
            closed: closed.is_some_and(|t| t.text == "closed"),
            alpha: alpha.map_or(0.0, |(_, value)| value),
            degree: degree.map_or(DEFAULT_NURBS_DEGREE, |(_, d)| d),
            knots: knots.map(|(_, values)| values),
        })
    }

    /// Reads the knot vector after the word `knots` of a NURBS of `degree`: NPOINTS + degree
    /// + 1 non-decreasing numbers, in brackets if `in_brackets` (`[knots …]`) or if a `[`
    ///   follows (`knots […]`), that leave the curve's domain non-empty.
    fn knots(&mut self, header: &Header<'a, '_>, degree: u32, in_brackets: bool) -> Result<Vec<f64>, SwpError> {
        let label = header.label;
        let knots_pos = self.tokens.get(self.next.saturating_sub(1)).map_or_else(|| self.end_pos(), |t| t.pos);
        // the count rule first, so that the number of knots to read is sane
        self.check_count(header, SwpCurveKind::Nurbs { degree }, false)?;
        let n = header.count;
        let expected_count = n + u64::from(degree) + 1;
        let in_brackets = in_brackets
            || match self.peek() {
                Some(token) if token.kind == TokenKind::Open => {
                    self.next += 1;
                    true
                }
                _ => false,
            };
        let rule = || format!("NPOINTS + degree + 1 = {n} + {degree} + 1");
        let capacity = usize::try_from(expected_count).unwrap_or(usize::MAX).min(self.remaining());
        let mut values: Vec<f64> = Vec::with_capacity(capacity);
        for k in 1..=expected_count {
            let expected = || format!("a number (knot {k} of the {expected_count} knots, {}, of {label})", rule());
            let token = self.expect(expected)?;
            let value = number(token.text).ok_or_else(|| self.invalid_number(token, expected()))?;
            if let Some(&before) = values.last()
                && value < before
            {
                return Err(self
                    .invalid_number(token, format!("a knot ≥ {before} (knot {k} of {label}; knots never decrease)")));
            }
            values.push(value);
        }
        let extra_knot = |token: Token<'_>| token.kind == TokenKind::Word && number(token.text).is_some();
        if in_brackets {
            let expected = || format!("`]` closing the {expected_count} knots ({}) of {label}", rule());
            let close = self.expect(expected)?;
            if close.kind != TokenKind::Close {
                return Err(self.unexpected(close, expected()));
            }
        } else if let Some(token) = self.peek().filter(|t| extra_knot(*t)) {
            return Err(self.unexpected(
                token,
                format!("`[` starting point 1 of {label}, after its {expected_count} knots ({})", rule()),
            ));
        }
        // the domain runs from knot `degree + 1` to knot `n + 1` (1-based)
        let (first, last) = (degree as usize, usize::try_from(n).unwrap_or(usize::MAX));
        if values[first] >= values[last] {
            return Err(self.error(
                knots_pos,
                SwpErrorKind::BadOption {
                    found: "knots".to_owned(),
                    expected: format!(
                        "a knot vector whose knot {} is less than its knot {} for {label}: the curve runs between \
                         them, and they are both {}",
                        first + 1,
                        last + 1,
                        values[first]
                    ),
                },
            ));
        }
        Ok(values)
    }

    /// Reads `[x y]` or `[x y z]`: the `role` (point or tangent) number `n` of `label`.
    fn point(&mut self, dim: u8, role: &str, n: u64, count: u64, label: &str) -> Result<DVec3, SwpError> {
        Ok(self.bracketed(dim, Extra::None, role, n, count, label)?.0)
    }

    /// Reads `[x y]` or `[x y z]`, followed before the `]` by the `extra` numbers (a tension,
    /// continuity and bias, each from −1 to 1, or a weight > 0): the `role` (point or tangent)
    /// number `n` of `label`. The extra numbers come first in the array.
    fn bracketed(
        &mut self,
        dim: u8,
        extra: Extra,
        role: &str,
        n: u64,
        count: u64,
        label: &str,
    ) -> Result<(DVec3, [f64; 3]), SwpError> {
        let expected_open = || format!("`[` starting {role} {n} of {count} of {label}");
        let open = self.expect(expected_open)?;
        if open.kind != TokenKind::Open {
            return Err(self.unexpected(open, expected_open()));
        }
        let mut xyz = [0.0; 3];
        for (axis, slot) in ["x", "y", "z"].into_iter().zip(xyz.iter_mut()).take(usize::from(dim)) {
            let expected = || format!("a number ({axis} coordinate of {role} {n} of {label})");
            let token = self.expect(expected)?;
            *slot = number(token.text).ok_or_else(|| self.invalid_number(token, expected()))?;
        }
        let form = extra.form(dim);
        let mut values = [0.0; 3];
        for (what, slot) in extra.names().iter().zip(values.iter_mut()) {
            let (range, ok): (&str, fn(f64) -> bool) = match extra {
                Extra::Weight => ("a number > 0", |v| v > 0.0),
                Extra::Shape | Extra::None => ("a number from -1 to 1", |v| (-1.0..=1.0).contains(&v)),
            };
            let expected = || format!("{range} (the {what} of {role} {n} of {label}, whose points are {form})");
            let token = self.expect(expected)?;
            *slot = number(token.text).filter(|&v| ok(v)).ok_or_else(|| self.invalid_number(token, expected()))?;
        }
        let expected_close = || format!("`]` closing {role} {n} of {label}");
        let close = self.expect(expected_close)?;
        if close.kind != TokenKind::Close {
            let shape = if extra == Extra::None {
                format!("its points have {dim} coordinates")
            } else {
                format!("its points are {form}")
            };
            return Err(self.unexpected(close, format!("{} ({shape})", expected_close())));
        }
        Ok((DVec3::from_array(xyz), values))
    }

    /// Reads a number that must satisfy `ok`; `what` describes it, like `a radius (a number ≥ 0)`.
    fn value(&mut self, what: &str, label: &str, ok: impl Fn(f64) -> bool) -> Result<f64, SwpError> {
        let expected = || format!("{what} for {label}");
        let token = self.expect(expected)?;
        number(token.text).filter(|&v| ok(v)).ok_or_else(|| self.invalid_number(token, expected()))
    }

    /// `circ NAME STEPS RADIUS`, after the keyword.
    fn circle(&mut self, pos: SourcePos) -> Result<(), SwpError> {
        let index = self.doc.curves.len();
        let (name, name_pos) = self.name("circ curve")?;
        let label = label("circ", "curve", name, index);
        let steps = self.steps(&label)?;
        let radius = self.value("a radius (a number ≥ 0)", &label, |r| r >= 0.0)?;
        self.register(name, name_pos, Named::Curve(index));
        self.doc.curves.push(SwpCurve {
            name: name.map(str::to_owned),
            kind: SwpCurveKind::Circle,
            dim: 2,
            steps,
            closed: true,
            geometry: SwpGeometry::Circle { radius },
            pos,
        });
        Ok(())
    }

    /// `helix NAME STEPS RADIUS PITCH TURNS`, after the keyword.
    fn helix(&mut self, pos: SourcePos) -> Result<(), SwpError> {
        let index = self.doc.curves.len();
        let (name, name_pos) = self.name("helix curve")?;
        let label = label("helix", "curve", name, index);
        let steps = self.steps(&label)?;
        let radius = self.value("a radius (a number ≥ 0)", &label, |r| r >= 0.0)?;
        let pitch = self.value("a pitch (the rise per turn, a number)", &label, |_| true)?;
        let turns =
            self.value(&format!("a number of turns (a number > 0 and ≤ {MAX_HELIX_TURNS})"), &label, |t| {
                t > 0.0 && t <= MAX_HELIX_TURNS
            })?;
        self.register(name, name_pos, Named::Curve(index));
        self.doc.curves.push(SwpCurve {
            name: name.map(str::to_owned),
            kind: SwpCurveKind::Helix,
            dim: 3,
            steps,
            closed: false,
            geometry: SwpGeometry::Helix { radius, pitch, turns },
            pos,
        });
        Ok(())
    }

    /// `trefoil NAME STEPS SIZE`, after the keyword.
    fn trefoil(&mut self, pos: SourcePos) -> Result<(), SwpError> {
        let index = self.doc.curves.len();
        let (name, name_pos) = self.name("trefoil curve")?;
        let label = label("trefoil", "curve", name, index);
        let steps = self.steps(&label)?;
        let size = self.value("a size (a number ≥ 0)", &label, |s| s >= 0.0)?;
        self.register(name, name_pos, Named::Curve(index));
        self.doc.curves.push(SwpCurve {
            name: name.map(str::to_owned),
            kind: SwpCurveKind::Trefoil,
            dim: 3,
            steps,
            closed: true,
            geometry: SwpGeometry::Trefoil { size },
            pos,
        });
        Ok(())
    }

    /// `srev NAME STEPS PROFILE`, after the keyword.
    fn revolution(&mut self, pos: SourcePos) -> Result<(), SwpError> {
        let index = self.doc.surfaces.len();
        let (name, name_pos) = self.name("srev surface")?;
        let label = label("srev", "surface", name, index);
        let steps = self.steps(&label)?;
        let profile = self.reference(&label, Role::Profile)?;
        let mut settings = SwpSurfaceSettings::default();
        let mut seen = Seen::default();
        while self.setting("srev", &label, &mut settings, &mut seen)? {}
        self.register(name, name_pos, Named::Surface(index));
        self.doc.surfaces.push(SwpSurface {
            name: name.map(str::to_owned),
            kind: SwpSurfaceKind::Revolution { steps, profile },
            settings,
            pos,
        });
        Ok(())
    }

    /// `gcyl NAME PROFILE SWEEP clause*`, after the keyword.
    ///
    /// A clause starts with the word `scale` or `twist` right after SWEEP (or after another
    /// clause). No object starts with these words, so whatever else follows ends the gcyl.
    fn cylinder(&mut self, pos: SourcePos) -> Result<(), SwpError> {
        let index = self.doc.surfaces.len();
        let (name, name_pos) = self.name("gcyl surface")?;
        let label = label("gcyl", "surface", name, index);
        let profile = self.reference(&label, Role::Profile)?;
        let sweep = self.reference(&label, Role::Sweep)?;
        let mut scale: Option<(Token<'a>, usize)> = None;
        let mut twist: Option<(Token<'a>, usize)> = None;
        let mut settings = SwpSurfaceSettings::default();
        let mut seen = Seen::default();
        while let Some(token) = self.peek().filter(|t| t.kind == TokenKind::Word) {
            let (slot, role) = match token.text {
                "scale" => (&mut scale, Role::Clause(SwpClause::Scale)),
                "twist" => (&mut twist, Role::Clause(SwpClause::Twist)),
                _ if self.setting("gcyl", &label, &mut settings, &mut seen)? => continue,
                _ => break,
            };
            if let Some((first, _)) = *slot {
                let message = format!(
                    "at most one {} clause for {label} (already given at line {}, column {})",
                    token.text, first.pos.line, first.pos.column
                );
                return Err(self.bad_option(token, message));
            }
            self.next += 1;
            *slot = Some((token, self.reference(&label, role)?));
        }
        self.register(name, name_pos, Named::Surface(index));
        self.doc.surfaces.push(SwpSurface {
            name: name.map(str::to_owned),
            kind: SwpSurfaceKind::GeneralizedCylinder {
                profile,
                sweep,
                scale: scale.map(|(_, curve)| curve),
                twist: twist.map(|(_, curve)| curve),
            },
            settings,
            pos,
        });
        Ok(())
    }

    /// `zrev NAME PROFILE option*`, after the keyword; the options `epsilon E`,
    /// `slice-tolerance T` and `scale S` (each a number > 0, at most once, any order).
    fn revolution_z(&mut self, pos: SourcePos) -> Result<(), SwpError> {
        let index = self.doc.surfaces.len();
        let (name, name_pos) = self.name("zrev surface")?;
        let label = label("zrev", "surface", name, index);
        let profile = self.reference(&label, Role::Profile)?;
        let mut values: [Option<(Token<'a>, f64)>; 3] = [None; 3];
        const WORDS: [&str; 3] = ["epsilon", "slice-tolerance", "scale"];
        let mut settings = SwpSurfaceSettings::default();
        let mut seen = Seen::default();
        while let Some(token) = self.peek().filter(|t| t.kind == TokenKind::Word) {
            let Some(k) = WORDS.iter().position(|&w| w == token.text) else {
                if self.setting("zrev", &label, &mut settings, &mut seen)? {
                    continue;
                }
                break;
            };
            if let Some((first, _)) = values[k] {
                return Err(self.bad_option(token, already(&label, first, token.text)));
            }
            self.next += 1;
            let value = match k {
                0 => self.value("an angle tolerance in radians (a number > 0)", &label, |v| v > 0.0)?,
                // at most MAX_STEPS slices
                1 => self.value(
                    &format!("a slice tolerance in radians (a number ≥ 2π/{MAX_STEPS}, at most {MAX_STEPS} slices)"),
                    &label,
                    |v| v > 0.0 && std::f64::consts::TAU / v <= f64::from(MAX_STEPS),
                )?,
                _ => self.value("a scale (a number > 0)", &label, |v| v > 0.0)?,
            };
            values[k] = Some((token, value));
        }
        self.register(name, name_pos, Named::Surface(index));
        self.doc.surfaces.push(SwpSurface {
            name: name.map(str::to_owned),
            kind: SwpSurfaceKind::RevolutionZ {
                profile,
                epsilon: values[0].map_or(DEFAULT_ZREV_EPSILON, |(_, v)| v),
                slice_tolerance: values[1].map_or(DEFAULT_ZREV_SLICE_TOLERANCE, |(_, v)| v),
                scale: values[2].map_or(1.0, |(_, v)| v),
            },
            settings,
            pos,
        });
        Ok(())
    }

    /// `xsweep NAME PROFILE PATH option*`, after the keyword; the options `epsilon E`,
    /// `path-epsilon E` and `scale S` (each a number > 0, at most once, any order) and the
    /// `layout` setting.
    fn tool_sweep(&mut self, pos: SourcePos) -> Result<(), SwpError> {
        let index = self.doc.surfaces.len();
        let (name, name_pos) = self.name("xsweep surface")?;
        let label = label("xsweep", "surface", name, index);
        let profile = self.reference(&label, Role::Profile)?;
        let path = self.reference(&label, Role::Sweep)?;
        let mut values: [Option<(Token<'a>, f64)>; 3] = [None; 3];
        const WORDS: [&str; 3] = ["epsilon", "path-epsilon", "scale"];
        let mut settings = SwpSurfaceSettings::default();
        let mut seen = Seen::default();
        while let Some(token) = self.peek().filter(|t| t.kind == TokenKind::Word) {
            let Some(k) = WORDS.iter().position(|&w| w == token.text) else {
                if self.setting("xsweep", &label, &mut settings, &mut seen)? {
                    continue;
                }
                break;
            };
            if let Some((first, _)) = values[k] {
                return Err(self.bad_option(token, already(&label, first, token.text)));
            }
            self.next += 1;
            let what = if k == 2 { "a scale (a number > 0)" } else { "an angle tolerance in radians (a number > 0)" };
            values[k] = Some((token, self.value(what, &label, |v| v > 0.0)?));
        }
        self.register(name, name_pos, Named::Surface(index));
        self.doc.surfaces.push(SwpSurface {
            name: name.map(str::to_owned),
            kind: SwpSurfaceKind::ToolSweep {
                profile,
                path,
                epsilon: values[0].map_or(DEFAULT_XSWEEP_EPSILON, |(_, v)| v),
                path_epsilon: values[1].map_or(DEFAULT_XSWEEP_EPSILON, |(_, v)| v),
                scale: values[2].map_or(1.0, |(_, v)| v),
            },
            settings,
            pos,
        });
        Ok(())
    }

    /// `lathe NAME STEPS SLICES RADIUS HEIGHT`, after the keyword.
    fn lathe(&mut self, pos: SourcePos) -> Result<(), SwpError> {
        let index = self.doc.surfaces.len();
        let (name, name_pos) = self.name("lathe surface")?;
        let label = label("lathe", "surface", name, index);
        let stacks = self.steps(&label)?;
        let expected = || format!("a slice count (an integer from 3 to {MAX_STEPS}) for {label}");
        let token = self.expect(expected)?;
        let slices = int_value(token.text)
            .and_then(|v| u32::try_from(v).ok())
            .filter(|n| (3..=MAX_STEPS).contains(n))
            .ok_or_else(|| self.invalid_number(token, expected()))?;
        let radius = self.reference(&label, Role::Radius)?;
        let height = self.reference(&label, Role::Height)?;
        let mut settings = SwpSurfaceSettings::default();
        let mut seen = Seen::default();
        while self.setting("lathe", &label, &mut settings, &mut seen)? {}
        self.register(name, name_pos, Named::Surface(index));
        self.doc.surfaces.push(SwpSurface {
            name: name.map(str::to_owned),
            kind: SwpSurfaceKind::Lathe { stacks, slices, radius, height },
            settings,
            pos,
        });
        Ok(())
    }

    /// Reads one setting of the surface `label` (whose keyword is `keyword`) if the next
    /// token is a setting word: `tolerance D`, `angle-tolerance DEGREES`, `layout
    /// welded|compat`, `frames sequential|rmf|frenet|zup`, `caps` or `no-caps`, `align
    /// origin|centre|center|start`, `join mitre|miter|round|bevel`, `mitre-limit R`. Returns
    /// whether it read
    /// one. A setting given twice (or both tolerances), or one that does not apply to the
    /// kind, is an error.
    fn setting(
        &mut self,
        keyword: &str,
        label: &str,
        settings: &mut SwpSurfaceSettings,
        seen: &mut Seen<'a>,
    ) -> Result<bool, SwpError> {
        let Some(token) = self.peek().filter(|t| t.kind == TokenKind::Word) else { return Ok(false) };
        let word = if token.text == "no-caps" { "caps" } else { token.text };
        let Some(&(_, kinds)) = SETTING_WORDS.iter().find(|(w, _)| *w == word) else { return Ok(false) };
        if !kinds.contains(&keyword) {
            let expected = format!("a setting of {label} ({} applies to {} only)", token.text, kinds.join(", "));
            return Err(self.bad_option(token, expected));
        }
        let group = match word {
            "tolerance" | "angle-tolerance" => 0,
            "layout" => 1,
            "frames" => 2,
            "align" => 4,
            "join" => 5,
            "mitre-limit" => 6,
            "scale-mode" => 7,
            _ => 3,
        };
        if let Some(first) = seen[group] {
            let groups = [
                "tolerance or angle-tolerance",
                "layout",
                "frames",
                "caps or no-caps",
                "align",
                "join",
                "mitre-limit",
                "scale-mode",
            ];
            return Err(self.bad_option(token, already(label, first, groups[group])));
        }
        seen[group] = Some(token);
        self.next += 1;
        let mut choice = |options: &[&str], what: &str| -> Result<usize, SwpError> {
            let expected = || format!("{} for the {what} of {label}", options.join(" or "));
            let value = self.expect(expected)?;
            options.iter().position(|&o| o == value.text).ok_or_else(|| self.bad_option(value, expected()))
        };
        match token.text {
            "tolerance" => {
                let d = self.value("a distance tolerance (a number > 0)", label, |v| v > 0.0)?;
                settings.tessellation = Some(SwpTessellation::Distance(d));
            }
            "angle-tolerance" => {
                let a = self.value("an angle tolerance in degrees (more than 0, at most 180)", label, |v| {
                    v > 0.0 && v <= 180.0
                })?;
                settings.tessellation = Some(SwpTessellation::AngleDegrees(a));
            }
            "layout" => {
                let k = choice(&["welded", "compat"], "layout")?;
                settings.layout = Some([MeshLayout::Welded, MeshLayout::Compat][k]);
            }
            "frames" => {
                let k = choice(&["auto", "sequential", "rmf", "frenet", "zup"], "frames")?;
                settings.frames = Some(
                    [
                        SwpFrames::Auto,
                        SwpFrames::Sequential,
                        SwpFrames::RotationMinimizing,
                        SwpFrames::Frenet,
                        SwpFrames::ZUp,
                    ][k],
                );
            }
            "align" => {
                let k = choice(&["origin", "centre", "center", "start"], "align")?;
                settings.align =
                    Some([ProfileAlign::Origin, ProfileAlign::Centre, ProfileAlign::Centre, ProfileAlign::Start][k]);
            }
            "join" => {
                let k = choice(&["mitre", "miter", "round", "bevel"], "join")?;
                settings.join = Some([Join::Mitre, Join::Mitre, Join::Round, Join::Bevel][k]);
            }
            "mitre-limit" => {
                let r = self.value("a mitre limit (a number ≥ 1)", label, |v| v >= 1.0)?;
                settings.mitre_limit = Some(r);
            }
            "scale-mode" => {
                let k = choice(&["multiply", "override"], "scale mode")?;
                settings.scale_mode = Some([ScaleMode::Multiply, ScaleMode::Override][k]);
            }
            "caps" => settings.caps = Some(true),
            _ => settings.caps = Some(false),
        }
        Ok(true)
    }

    /// Reads a reference to a curve defined earlier, for `role` in the surface `label`
    /// (profiles, scale and twist curves must be 2D).
    fn reference(&mut self, label: &str, role: Role) -> Result<usize, SwpError> {
        let expected = || format!("the name of the {} curve of {label}", role.name());
        let token = self.expect(expected)?;
        if token.kind != TokenKind::Word {
            return Err(self.unexpected(token, expected()));
        }
        let undefined = |why: &str| {
            self.error(
                token.pos,
                SwpErrorKind::UndefinedName {
                    name: token.text.to_owned(),
                    expected: format!("{} ({why})", expected()),
                },
            )
        };
        let index = match self.names.get(token.text) {
            Some(&(Named::Curve(index), _)) => index,
            Some(&(Named::Surface(_), _)) => return Err(undefined("this name is a surface")),
            None if token.text == "." => {
                return Err(undefined("anonymous curves cannot be referenced"));
            }
            None => return Err(undefined("no curve of this name is defined before it")),
        };
        if let Some(curve) = self.doc.curves.get(index).filter(|c| c.dim != 2) {
            let (name, keyword, surface) = (token.text.to_owned(), curve.keyword(), label.to_owned());
            let kind = match role {
                Role::Sweep => return Ok(index),
                Role::Profile => SwpErrorKind::ProfileNot2D { name, keyword, surface },
                Role::Clause(role) => SwpErrorKind::CurveNot2D { name, keyword, role, surface },
                Role::Radius => SwpErrorKind::LatheCurveNot2D { name, keyword, role: SwpCurveRole::Radius, surface },
                Role::Height => SwpErrorKind::LatheCurveNot2D { name, keyword, role: SwpCurveRole::Height, surface },
            };
            return Err(self.error(token.pos, kind));
        }
        Ok(index)
    }
}

/// What a surface uses a curve for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Role {
    Profile,
    Sweep,
    Clause(SwpClause),
    Radius,
    Height,
}

impl Role {
    fn name(self) -> &'static str {
        match self {
            Self::Profile => "profile",
            Self::Sweep => "sweep",
            Self::Clause(clause) => clause.keyword(),
            Self::Radius => "radius",
            Self::Height => "height",
        }
    }
}

/// An option word: `closed`/`open`, or a parametrization (`alpha` reads its value: `None`).
#[derive(Debug, Clone, Copy)]
enum OptionWord {
    Openness,
    Alpha(Option<f64>),
    Degree,
    Knots,
}

/// The options read for one curve.
#[derive(Debug, Clone)]
struct CurveOptions {
    closed: bool,
    alpha: f64,
    degree: u32,
    knots: Option<Vec<f64>>,
}

/// What a curve's header said before its options: the keyword, its family, the label for
/// messages and NPOINTS with its token.
#[derive(Clone, Copy)]
struct Header<'a, 'l> {
    keyword: &'static str,
    family: Family,
    label: &'l str,
    count: u64,
    count_token: Token<'a>,
}

/// The numbers a point carries inside its brackets after its coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Extra {
    None,
    /// Tension, continuity and bias (Kochanek–Bartels).
    Shape,
    /// A weight (NURBS).
    Weight,
}

impl Extra {
    /// The names of the extra numbers, in order.
    fn names(self) -> &'static [&'static str] {
        match self {
            Self::None => &[],
            Self::Shape => &["tension", "continuity", "bias"],
            Self::Weight => &["weight"],
        }
    }

    /// A point's form in words, like `[x y w]`.
    fn form(self, dim: u8) -> &'static str {
        match (self, dim == 3) {
            (Self::None, false) => "[x y]",
            (Self::None, true) => "[x y z]",
            (Self::Shape, false) => "[x y t c b]",
            (Self::Shape, true) => "[x y z t c b]",
            (Self::Weight, false) => "[x y w]",
            (Self::Weight, true) => "[x y z w]",
        }
    }
}

/// The options a family accepts, for messages.
fn option_list(family: Family) -> &'static str {
    match family {
        Family::CatmullRom => "closed, open, alpha A, uniform, centripetal or chordal",
        Family::Nurbs => "closed, open, degree D or knots K…",
        Family::BezierN => "open",
        _ => "closed or open",
    }
}

/// The message for `knots` and `closed` on one curve.
fn periodic_with_knots(label: &str, first: Token<'_>) -> String {
    format!(
        "`[` starting point 1 of {label}: a closed NURBS is periodic with uniform knots of its own, so it takes no \
         `knots` (line {}, column {} has the other)",
        first.pos.line, first.pos.column
    )
}

/// "… at most one of `group` …" message for an option given twice.
fn already(label: &str, first: Token<'_>, group: &str) -> String {
    format!(
        "at most one of {group} for {label} (already given as {:?} at line {}, column {})",
        first.text, first.pos.line, first.pos.column
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integers() {
        assert_eq!(int_value("20"), Some(20));
        assert_eq!(int_value("+7"), Some(7));
        assert_eq!(int_value("-3"), Some(-3));
        assert_eq!(int_value("007"), Some(7));
        assert_eq!(int_value("99999999999999999999999"), Some(i128::from(u64::MAX)));
        for bad in ["", "-", "+", "2.0", "1e3", "x", "--1", "+-1", "٣"] {
            assert_eq!(int_value(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn numbers() {
        assert_eq!(number("-0.765483"), Some(-0.765483));
        assert_eq!(number("2"), Some(2.0));
        assert_eq!(number("1e-3"), Some(1e-3));
        assert_eq!(number(".5"), Some(0.5));
        assert_eq!(number("5."), Some(5.0));
        for bad in ["nan", "NaN", "inf", "-inf", "infinity", "1e999", "1.2.3", "", "[", "0x10", "1,5"] {
            assert_eq!(number(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn count_rules() {
        let accepted = |family: Family, closed: bool| -> Vec<u64> {
            (0..12).filter(|&n| family.kind(0.5, 3).accepts_point_count(closed, n)).collect()
        };
        assert_eq!(accepted(Family::Bezier, false), [4, 7, 10]);
        assert_eq!(accepted(Family::Bezier, true), [3, 6, 9]);
        for family in [Family::BSpline, Family::CatmullRom, Family::KochanekBartels, Family::BesselOverhauser] {
            assert_eq!(accepted(family, false), (4..12).collect::<Vec<_>>());
            assert_eq!(accepted(family, true), (3..12).collect::<Vec<_>>());
        }
        assert_eq!(accepted(Family::Hermite, false), (2..12).collect::<Vec<_>>());
        assert_eq!(accepted(Family::Hermite, true), (2..12).collect::<Vec<_>>());
        assert!(SwpCurveKind::BSpline.accepts_point_count(false, u64::MAX));
        for kind in [SwpCurveKind::Circle, SwpCurveKind::Helix, SwpCurveKind::Trefoil] {
            assert!(kind.accepts_point_count(true, 0) && !kind.accepts_point_count(true, 4));
        }
    }

    #[test]
    fn keywords_are_known() {
        for word in KEYWORDS {
            assert!(keyword(word).is_some(), "{word}");
        }
        assert!(keyword("BEZ2").is_none());
        assert!(keyword("bez4").is_none());
    }
}
