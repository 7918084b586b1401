//! Structure-aware SWP documents: every curve keyword (`bez2 bsp2 cr2 her2 tcb2 bo2 bezn2 nurbs2
//! bez3 bsp3 cr3 her3 tcb3 bo3 bezn3 nurbs3 circ helix trefoil`), every surface keyword (`srev gcyl zrev xsweep lathe`) with their
//! options, clauses and settings, comments and every whitespace the format allows, filled
//! with ordinary and extreme values. Most documents follow the grammar (so that they reach
//! the geometry); a few break one rule (so that the errors are exercised too).

use crate::rng::Rng;
use crate::values::{self, EXTREMES, Scale};

/// What a defined curve can serve as.
#[derive(Clone, Debug)]
struct Defined {
    /// Its name (`None` for `.`, which cannot be referenced).
    name: Option<String>,
    /// The keyword.
    keyword: &'static str,
}

/// A document being written.
struct Doc<'a> {
    rng: &'a mut Rng,
    text: String,
    curves: Vec<Defined>,
    names: Vec<String>,
    scale: Scale,
    /// Probability of breaking a rule at a given place.
    mistakes: f64,
}

/// The curve keywords, with their dimension.
const CURVES: [(&str, u8); 19] = [
    ("bez2", 2),
    ("bsp2", 2),
    ("cr2", 2),
    ("her2", 2),
    ("tcb2", 2),
    ("bo2", 2),
    ("bez3", 3),
    ("bsp3", 3),
    ("cr3", 3),
    ("her3", 3),
    ("tcb3", 3),
    ("bo3", 3),
    ("bezn2", 2),
    ("bezn3", 3),
    ("nurbs2", 2),
    ("nurbs3", 3),
    ("circ", 2),
    ("helix", 3),
    ("trefoil", 3),
];

/// Names that look like keywords, numbers or option words (all valid names).
const ODD_NAMES: [&str; 14] = [
    "scale",
    "twist",
    "bez2",
    "circ",
    "srev",
    "closed",
    "12",
    "-1",
    "1e5",
    "tolerance",
    "layout",
    "caps",
    "epsilon",
    "profile",
];

/// An SWP document as text.
pub fn generate(rng: &mut Rng) -> String {
    let scale = Scale::draw(rng);
    let mistakes = if rng.chance(0.7) { 0.0 } else { 0.02 };
    let mut doc = Doc { rng, text: String::new(), curves: Vec::new(), names: Vec::new(), scale, mistakes };
    if doc.rng.chance(0.05) {
        doc.text.push('\u{feff}');
    }
    let objects = doc.rng.size(1, 24);
    for _ in 0..objects {
        if doc.curves.is_empty() || doc.rng.chance(0.55) {
            doc.curve(None);
        } else {
            doc.surface();
        }
        if doc.rng.chance(0.5) {
            doc.text.push('\n');
        }
    }
    if doc.rng.chance(0.3) {
        let end = *doc.rng.pick(&["", "\n", "\r\n", "   ", "\n\n\t\n", "# the end"]);
        doc.text.push_str(end);
    }
    doc.text
}

impl Doc<'_> {
    /// Whether to break a rule here.
    fn mistake(&mut self) -> bool {
        self.mistakes > 0.0 && self.rng.chance(self.mistakes)
    }

    /// Appends one token after some whitespace (and now and then a comment).
    fn tok(&mut self, token: &str) {
        if !self.text.is_empty() && !self.text.ends_with('\n') {
            let space = values::space(self.rng);
            self.text.push_str(space);
        }
        self.text.push_str(token);
        if self.rng.chance(0.01) {
            let glued = self.rng.chance(0.5);
            self.text.push_str(if glued { "# note ] [ 1 2\n" } else { " #comment\r\n" });
        }
    }

    /// A number token.
    fn num(&mut self, x: f64) {
        let text = values::format(self.rng, x);
        self.tok(&text);
    }

    /// An integer token such as STEPS or a count, now and then out of range or malformed.
    fn int(&mut self, n: u64) {
        if self.mistake() {
            let bad = *self.rng.pick(&["0", "-1", "1000001", "1.5", "1e3", "99999999999999999999", "x"]);
            self.tok(bad);
        } else {
            self.tok(&n.to_string());
        }
    }

    /// STEPS: usually small, now and then the extremes the format allows.
    fn steps(&mut self) -> u64 {
        match self.rng.below(20) {
            0 => *self.rng.pick(&[1, 2, 65_536, 65_537, 999_999, 1_000_000]),
            1..=3 => self.rng.range(1, 4) as u64,
            _ => self.rng.size(1, 200) as u64,
        }
    }

    /// A name for a new object: `.`, a fresh name, or an odd one (long, Unicode, keyword-like,
    /// now and then a duplicate, which is an error).
    fn new_name(&mut self) -> Option<String> {
        let name = match self.rng.below(12) {
            0..=2 => return None,
            3 => (*self.rng.pick(&ODD_NAMES)).to_owned(),
            4 => "n".repeat(self.rng.size(1, 5000)),
            5 => format!("αβγ-名前-{}", self.names.len()),
            6 if !self.names.is_empty() && self.mistake() => self.rng.pick(&self.names).clone(),
            _ => format!("c{}", self.names.len()),
        };
        if self.names.contains(&name) && !self.mistake() {
            return Some(format!("{name}_{}", self.names.len()));
        }
        Some(name)
    }

    fn name_token(&mut self, name: &Option<String>) {
        match name {
            Some(n) => self.tok(&n.clone()),
            None => self.tok("."),
        }
    }

    /// Defines a curve (of `keyword`, or a random kind) and returns its index.
    fn curve(&mut self, keyword: Option<&'static str>) -> usize {
        let (keyword, dim) = match keyword {
            Some(k) => *CURVES.iter().find(|(c, _)| *c == k).unwrap_or(&CURVES[0]),
            None => *self.rng.pick(&CURVES),
        };
        let name = self.new_name();
        self.tok(keyword);
        self.name_token(&name);
        let steps = self.steps();
        self.int(steps);
        match keyword {
            "circ" => {
                let r = values::positive(self.rng, self.scale.magnitude);
                self.num(r);
            }
            "helix" => {
                let r = values::positive(self.rng, self.scale.magnitude);
                self.num(r);
                let pitch = self.scale.coord(self.rng);
                self.num(pitch);
                let turns = match self.rng.below(10) {
                    0 => *self.rng.pick(&[1e-300, 1e-9, 10_000.0, 9_999.999, 0.0, 10_001.0, -1.0]),
                    _ => self.rng.uniform(0.1, 12.0),
                };
                self.num(turns);
            }
            "trefoil" => {
                let size = values::positive(self.rng, self.scale.magnitude);
                self.num(size);
            }
            _ => self.control_points(keyword, dim),
        }
        if let Some(n) = &name {
            self.names.push(n.clone());
        }
        self.curves.push(Defined { name, keyword });
        self.curves.len() - 1
    }

    /// NPOINTS, options and the points (pairs for Hermite curves, with tension, continuity and
    /// bias for Kochanek–Bartels curves).
    fn control_points(&mut self, keyword: &str, dim: u8) {
        let bezn = keyword.starts_with("bezn");
        let nurbs = keyword.starts_with("nurbs");
        // a single Bézier curve is never closed
        let closed = self.rng.chance(0.3) && (!bezn || self.mistake());
        let hermite = keyword.starts_with("her");
        let degree = match self.rng.below(12) {
            0 if self.mistake() => *self.rng.pick(&[0, 33]),
            0 => *self.rng.pick(&[1, 7, 32]),
            _ => self.rng.range(1, 6),
        };
        let n = match &keyword[..2] {
            _ if bezn => self.rng.size(2, 65),
            "nu" => self.rng.size(degree.max(2) + 1, 120),
            "be" if closed => 3 * self.rng.size(1, 40),
            "be" => 3 * self.rng.size(1, 40) + 1,
            "he" => self.rng.size(2, 60),
            _ if closed => self.rng.size(3, 120),
            _ => self.rng.size(4, 120),
        };
        let declared = if self.mistake() { n + 1 } else { n };
        self.int(declared as u64);
        // options: open/closed, and the parametrization of Catmull-Rom curves
        let mut options: Vec<String> = Vec::new();
        if closed {
            options.push("closed".into());
        } else if self.rng.chance(0.1) {
            options.push("open".into());
        }
        if keyword.starts_with("cr") || self.mistake() {
            match self.rng.below(6) {
                0 => options.push("uniform".into()),
                1 => options.push("centripetal".into()),
                2 => options.push("chordal".into()),
                3 => {
                    let alpha = if self.mistake() { 1.5 } else { *self.rng.pick(&[0.0, 0.5, 1.0, 0.25, 1e-300]) };
                    options.push("alpha".into());
                    options.push(format!("{alpha}"));
                }
                _ => {}
            }
        }
        if self.rng.chance(0.5) {
            options.reverse();
        }
        if nurbs {
            // `degree` must come before `knots`; no knots on a closed curve
            options.push("degree".into());
            options.push(degree.to_string());
            if (!closed || self.mistake()) && self.rng.chance(0.5) {
                options.push("knots".into());
                options.extend(self.knots(n + degree + 1).iter().map(|k| values::format(self.rng, *k)));
            }
        }
        for o in options {
            self.tok(&o);
        }
        let points = self.point_set(n * if hermite { 2 } else { 1 }, dim);
        if nurbs {
            for p in points {
                let weight = match self.rng.below(10) {
                    0 if self.mistake() => *self.rng.pick(&[0.0, -1.0, -0.0]),
                    0 => *self.rng.pick(&[1e-300, 1e300, 5e-324, 1e-9, 1e9]),
                    1..=4 => 1.0,
                    _ => self.rng.uniform(0.05, 20.0),
                };
                self.key(&p, dim, &[weight]);
            }
            return;
        }
        if keyword.starts_with("tcb") {
            for p in points {
                let shape = self.shape();
                self.key(&p, dim, &shape);
            }
            return;
        }
        for p in points {
            self.point(&p, dim);
        }
    }

    /// `n` points of a shape: random, repeated, collinear, on a circle, nearly equal, or with
    /// an outlier.
    fn point_set(&mut self, n: usize, dim: u8) -> Vec<[f64; 3]> {
        let s = self.scale;
        let random = |rng: &mut Rng| [s.coord(rng), s.coord(rng), if dim == 3 { s.coord(rng) } else { 0.0 }];
        let a = random(self.rng);
        let d = random(self.rng);
        let mut points: Vec<[f64; 3]> = match self.rng.below(8) {
            0 => vec![a; n],
            1 => (0..n)
                .map(|_| {
                    let t = self.rng.uniform(-1.0, 2.0);
                    [a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]]
                })
                .collect(),
            2 => (0..n)
                .map(|i| {
                    let angle = std::f64::consts::TAU * i as f64 / n as f64;
                    [a[0] * angle.cos(), a[0] * angle.sin(), 0.0]
                })
                .collect(),
            3 => (0..n).map(|i| [a[0] + i as f64 * 1e-15 * a[0], a[1], a[2]]).collect(),
            4 => (0..n).map(|_| if self.rng.chance(0.5) { a } else { d }).collect(),
            _ => (0..n).map(|_| random(self.rng)).collect(),
        };
        if self.rng.chance(0.1) && !points.is_empty() {
            let i = self.rng.below(points.len());
            let k = self.rng.below(dim as usize);
            points[i][k] = *self.rng.pick(&EXTREMES);
        }
        points
    }

    /// A key's tension, continuity and bias: in [−1, 1], often 0 or ±1, now and then outside.
    fn shape(&mut self) -> [f64; 3] {
        [0; 3].map(|_| match self.rng.below(6) {
            0 => 0.0,
            1 => *self.rng.pick(&[-1.0, 1.0, -0.0, 1e-300]),
            _ if self.mistake() => *self.rng.pick(&[1.0000001, -2.0, 1e300]),
            _ => self.rng.uniform(-1.0, 1.0),
        })
    }

    /// `m` knots: non-decreasing, with repeats (clamped ends now and then, interior knots of
    /// any multiplicity), spans from tiny to huge; now and then one that decreases.
    fn knots(&mut self, m: usize) -> Vec<f64> {
        let s = self.scale;
        let mut k = s.coord(self.rng);
        let mut out = Vec::with_capacity(m);
        for _ in 0..m {
            out.push(k);
            k += match self.rng.below(8) {
                0..=2 => 0.0,
                3 => *self.rng.pick(&[1e-300, 1e-12, 1e12, 5e-324]),
                4 if self.mistake() => -1.0,
                _ => self.rng.uniform(0.0, s.magnitude.max(1e-300)),
            };
        }
        out
    }

    /// `[x y t c b]` or `[x y z t c b]` (a key and its shape), or `[x y w]` or `[x y z w]` (a
    /// NURBS point and its weight).
    fn key(&mut self, p: &[f64; 3], dim: u8, extra: &[f64]) {
        let mut t = String::from("[");
        for (k, x) in p.iter().take(dim as usize).chain(extra).enumerate() {
            if k > 0 {
                t.push(' ');
            }
            t.push_str(&values::format(self.rng, *x));
        }
        t.push(']');
        self.tok(&t);
    }

    /// `[x y]` or `[x y z]`, brackets glued or spaced.
    fn point(&mut self, p: &[f64; 3], dim: u8) {
        let glued = self.rng.chance(0.5);
        let mut t = String::from("[");
        for (k, x) in p.iter().take(dim as usize).enumerate() {
            if k > 0 || !glued {
                t.push(' ');
            }
            t.push_str(&values::format(self.rng, *x));
        }
        if !glued {
            t.push(' ');
        }
        t.push(']');
        if self.mistake() {
            t = t.replace(']', "");
        }
        self.tok(&t);
    }

    /// A named curve of one of `keywords` (with `dim` if given) to reference: an existing one,
    /// or one defined now; now and then any curve, or a name never defined.
    fn reference(&mut self, keywords: &[&'static str]) -> String {
        if self.mistake() {
            return match self.rng.below(3) {
                0 => "undefined".into(),
                1 => ".".into(),
                _ => self.names.first().cloned().unwrap_or_else(|| "x".into()),
            };
        }
        let fits: Vec<String> =
            self.curves.iter().filter(|c| keywords.contains(&c.keyword)).filter_map(|c| c.name.clone()).collect();
        if !fits.is_empty() && self.rng.chance(0.6) {
            return self.rng.pick(&fits).clone();
        }
        loop {
            let keyword = *self.rng.pick(keywords);
            let i = self.curve(Some(keyword));
            if let Some(name) = self.curves[i].name.clone() {
                return name;
            }
            // an anonymous curve cannot be referenced: define another
        }
    }

    /// A surface of a random kind with its options and settings.
    fn surface(&mut self) {
        const PROFILES: [&str; 9] = ["bez2", "bsp2", "cr2", "her2", "tcb2", "bo2", "bezn2", "nurbs2", "circ"];
        const SPLINES_2D: [&str; 6] = ["bez2", "bsp2", "cr2", "her2", "tcb2", "bo2"];
        const SWEEPS: [&str; 19] = [
            "bez2", "bsp2", "cr2", "her2", "tcb2", "bo2", "bezn2", "nurbs2", "circ", "bez3", "bsp3", "cr3", "her3",
            "tcb3", "bo3", "bezn3", "nurbs3", "helix", "trefoil",
        ];
        let kind = *self.rng.pick(&["srev", "gcyl", "zrev", "xsweep", "lathe"]);
        // the curves first (a reference may define one)
        let mut words: Vec<String> = Vec::new();
        match kind {
            "srev" => {
                let steps = self.steps();
                words.push(steps.to_string());
                words.push(self.reference(&PROFILES));
            }
            "gcyl" => {
                words.push(self.reference(&PROFILES));
                words.push(self.reference(&SWEEPS));
                for clause in ["scale", "twist"] {
                    if self.rng.chance(0.3) {
                        words.push(clause.into());
                        words.push(self.reference(&PROFILES));
                    }
                }
            }
            "zrev" => {
                words.push(self.reference(&SPLINES_2D));
                for option in ["epsilon", "slice-tolerance", "scale"] {
                    if self.rng.chance(0.4) {
                        words.push(option.into());
                        let x = values::positive(self.rng, 0.1);
                        words.push(values::format(self.rng, x));
                    }
                }
            }
            "xsweep" => {
                words.push(self.reference(&["bsp2"]));
                words.push(self.reference(&["bsp2"]));
                for option in ["epsilon", "path-epsilon", "scale"] {
                    if self.rng.chance(0.4) {
                        words.push(option.into());
                        let x = values::positive(self.rng, 0.05);
                        words.push(values::format(self.rng, x));
                    }
                }
            }
            _ => {
                let stacks = self.steps();
                words.push(stacks.to_string());
                let slices = match self.rng.below(10) {
                    0 => *self.rng.pick(&[3, 4, 1_000_000, 2]),
                    _ => self.rng.range(3, 64),
                };
                words.push(slices.to_string());
                words.push(self.reference(&["bez2"]));
                words.push(self.reference(&["bez2"]));
            }
        }
        self.settings(kind, &mut words);
        if self.rng.chance(0.5) && kind == "gcyl" {
            // clauses and settings mix in any order after the sweep
            let fixed = 2;
            if words.len() > fixed + 2 {
                let tail = words.split_off(fixed);
                let mut pairs: Vec<Vec<String>> = Vec::new();
                let mut it = tail.into_iter().peekable();
                while let Some(w) = it.next() {
                    let mut group = vec![w.clone()];
                    if matches!(
                        w.as_str(),
                        "scale"
                            | "twist"
                            | "tolerance"
                            | "angle-tolerance"
                            | "layout"
                            | "frames"
                            | "align"
                            | "join"
                            | "mitre-limit"
                            | "scale-mode"
                    ) && let Some(v) = it.next()
                    {
                        group.push(v);
                    }
                    pairs.push(group);
                }
                pairs.reverse();
                words.extend(pairs.into_iter().flatten());
            }
        }
        let name = self.new_name();
        self.tok(kind);
        self.name_token(&name);
        for w in words {
            self.tok(&w);
        }
        if let Some(n) = name {
            self.names.push(n);
        }
    }

    /// The surface settings of `kind` (each at most once, now and then a wrong one).
    fn settings(&mut self, kind: &str, words: &mut Vec<String>) {
        let tessellation = matches!(kind, "srev" | "gcyl" | "zrev" | "lathe");
        if tessellation || self.mistake() {
            match self.rng.below(5) {
                0 => {
                    words.push("tolerance".into());
                    let d = values::positive(self.rng, 1e-3 * self.scale.magnitude);
                    words.push(values::format(self.rng, d));
                }
                1 => {
                    words.push("angle-tolerance".into());
                    let a = match self.rng.below(6) {
                        0 => *self.rng.pick(&[180.0, 1e-300, 1e-9, 181.0, 0.0, -5.0]),
                        _ => self.rng.uniform(0.5, 60.0),
                    };
                    words.push(values::format(self.rng, a));
                }
                _ => {}
            }
        }
        if matches!(kind, "srev" | "gcyl" | "xsweep") && self.rng.chance(0.3) {
            words.push("layout".into());
            words.push((*self.rng.pick(&["welded", "compat"])).into());
        }
        if kind == "gcyl" || self.mistake() {
            if self.rng.chance(0.3) {
                words.push("frames".into());
                words.push((*self.rng.pick(&["sequential", "rmf", "frenet", "zup"])).into());
            }
            if self.rng.chance(0.3) {
                words.push((*self.rng.pick(&["caps", "no-caps"])).into());
            }
            if self.rng.chance(0.2) {
                words.push("align".into());
                words.push((*self.rng.pick(&["origin", "centre", "center", "start"])).into());
            }
            if self.rng.chance(0.2) {
                words.push("join".into());
                words.push((*self.rng.pick(&["mitre", "miter", "round", "bevel"])).into());
            }
            if self.rng.chance(0.1) {
                words.push("mitre-limit".into());
                words.push((*self.rng.pick(&["1", "2.5", "4", "100"])).into());
            }
        }
        if self.mistake() && !words.is_empty() {
            let i = self.rng.below(words.len());
            let w = words[i].clone();
            words.push(w);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn most_documents_parse() {
        let mut parsed = 0;
        let mut surfaces = 0;
        for i in 0..300 {
            let text = generate(&mut Rng::for_case(1, i));
            if let Ok(doc) = splinekit_io::SwpDocument::parse(&text, "g.swp") {
                parsed += 1;
                surfaces += doc.surfaces.len();
            }
        }
        assert!(parsed > 150, "only {parsed} of 300 generated documents parse");
        assert!(surfaces > 100, "only {surfaces} surfaces");
    }
}
