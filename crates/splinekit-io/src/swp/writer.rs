//! The SWP writer; see [`SwpDocument::to_swp_string`].

use crate::surface::{ProfileAlign, ScaleMode};
use std::collections::HashSet;
use std::fmt::Write as _;

use glam::DVec3;
use splinekit::sweep::{Join, MeshLayout};

use super::validate::name_problem;
use super::{
    DEFAULT_XSWEEP_EPSILON, DEFAULT_ZREV_EPSILON, DEFAULT_ZREV_SLICE_TOLERANCE, SwpCurve, SwpCurveKind, SwpDocument,
    SwpFrames, SwpGeometry, SwpSurfaceKind, SwpSurfaceSettings, SwpTessellation,
};

/// Whether `name` can be written as a NAME token that reads back as itself (the rule that
/// [`SwpDocument::validate`] applies too).
fn is_writable_name(name: &str) -> bool {
    name_problem(name).is_none()
}

/// Picks the name written for every curve and surface (`None` writes `.`).
fn output_names(doc: &SwpDocument) -> (Vec<Option<String>>, Vec<Option<String>>) {
    let referenced: HashSet<usize> =
        doc.surfaces.iter().flat_map(|s| s.kind.references().into_iter().map(|(_, curve)| curve)).collect();

    // First pass: keep every writable name at its first use.
    fn keep<'a>(taken: &mut HashSet<&'a str>, name: Option<&'a str>) -> Option<String> {
        name.filter(|n| is_writable_name(n) && taken.insert(n)).map(str::to_owned)
    }
    let mut taken = HashSet::new();
    let mut curves: Vec<Option<String>> = (doc.curves.iter()).map(|c| keep(&mut taken, c.name.as_deref())).collect();
    let mut surfaces: Vec<Option<String>> =
        (doc.surfaces.iter()).map(|s| keep(&mut taken, s.name.as_deref())).collect();

    // Second pass: generate names that clash with nothing kept or generated.
    let mut taken: HashSet<String> = curves.iter().chain(&surfaces).flatten().cloned().collect();
    let mut generate = |prefix: &str, index: usize| {
        let base = format!("_{prefix}{index}");
        let name = std::iter::once(base.clone())
            .chain((1..).map(|k| format!("{base}_{k}")))
            .find(|n| !taken.contains(n))
            .unwrap_or(base);
        taken.insert(name.clone());
        name
    };
    for (index, (out, curve)) in curves.iter_mut().zip(&doc.curves).enumerate() {
        if out.is_none() && (curve.name.is_some() || referenced.contains(&index)) {
            *out = Some(generate("c", index));
        }
    }
    for (index, (out, surface)) in surfaces.iter_mut().zip(&doc.surfaces).enumerate() {
        if out.is_none() && surface.name.is_some() {
            *out = Some(generate("s", index));
        }
    }
    (curves, surfaces)
}

/// Writes `doc` as SWP text; see [`SwpDocument::to_swp_string`].
pub(crate) fn write(doc: &SwpDocument) -> String {
    let (curve_names, surface_names) = output_names(doc);
    let mut out = String::new();
    for (curve, name) in doc.curves.iter().zip(&curve_names) {
        if !out.is_empty() {
            out.push('\n');
        }
        write_curve(&mut out, curve, name.as_deref().unwrap_or("."));
    }
    // A reference out of range is written as `.`, which never parses as a reference.
    let reference = |index: usize| curve_names.get(index).and_then(Option::as_deref).unwrap_or(".");
    for (surface, name) in doc.surfaces.iter().zip(&surface_names) {
        if !out.is_empty() {
            out.push('\n');
        }
        let name = name.as_deref().unwrap_or(".");
        // `fmt::Write` for `String` never fails.
        let _ = match surface.kind {
            SwpSurfaceKind::Revolution { steps, profile } => {
                write!(out, "srev {name} {steps} {}", reference(profile))
            }
            SwpSurfaceKind::GeneralizedCylinder { profile, sweep, scale, twist } => {
                let _ = write!(out, "gcyl {name} {} {}", reference(profile), reference(sweep));
                if let Some(scale) = scale {
                    let _ = write!(out, " scale {}", reference(scale));
                }
                if let Some(twist) = twist {
                    let _ = write!(out, " twist {}", reference(twist));
                }
                Ok(())
            }
            SwpSurfaceKind::RevolutionZ { profile, epsilon, slice_tolerance, scale } => {
                let _ = write!(out, "zrev {name} {}", reference(profile));
                if epsilon != DEFAULT_ZREV_EPSILON {
                    let _ = write!(out, " epsilon {epsilon}");
                }
                if slice_tolerance != DEFAULT_ZREV_SLICE_TOLERANCE {
                    let _ = write!(out, " slice-tolerance {slice_tolerance}");
                }
                if scale != 1.0 {
                    let _ = write!(out, " scale {scale}");
                }
                Ok(())
            }
            SwpSurfaceKind::ToolSweep { profile, path, epsilon, path_epsilon, scale } => {
                let _ = write!(out, "xsweep {name} {} {}", reference(profile), reference(path));
                if epsilon != DEFAULT_XSWEEP_EPSILON {
                    let _ = write!(out, " epsilon {epsilon}");
                }
                if path_epsilon != DEFAULT_XSWEEP_EPSILON {
                    let _ = write!(out, " path-epsilon {path_epsilon}");
                }
                if scale != 1.0 {
                    let _ = write!(out, " scale {scale}");
                }
                Ok(())
            }
            SwpSurfaceKind::Lathe { stacks, slices, radius, height } => {
                write!(out, "lathe {name} {stacks} {slices} {} {}", reference(radius), reference(height))
            }
        };
        write_settings(&mut out, &surface.settings);
        out.push('\n');
    }
    out
}

/// Writes a surface's settings, each after a space, in a fixed order.
fn write_settings(out: &mut String, settings: &SwpSurfaceSettings) {
    // `fmt::Write` for `String` never fails.
    match settings.tessellation {
        Some(SwpTessellation::Distance(d)) => {
            let _ = write!(out, " tolerance {d}");
        }
        Some(SwpTessellation::AngleDegrees(a)) => {
            let _ = write!(out, " angle-tolerance {a}");
        }
        None => {}
    }
    match settings.layout {
        Some(MeshLayout::Welded) => out.push_str(" layout welded"),
        Some(MeshLayout::Compat) => out.push_str(" layout compat"),
        None => {}
    }
    match settings.frames {
        Some(SwpFrames::Auto) => out.push_str(" frames auto"),
        Some(SwpFrames::Sequential) => out.push_str(" frames sequential"),
        Some(SwpFrames::RotationMinimizing) => out.push_str(" frames rmf"),
        Some(SwpFrames::Frenet) => out.push_str(" frames frenet"),
        Some(SwpFrames::ZUp) => out.push_str(" frames zup"),
        None => {}
    }
    match settings.caps {
        Some(true) => out.push_str(" caps"),
        Some(false) => out.push_str(" no-caps"),
        None => {}
    }
    match settings.align {
        Some(ProfileAlign::Origin) => out.push_str(" align origin"),
        Some(ProfileAlign::Centre) => out.push_str(" align centre"),
        Some(ProfileAlign::Start) => out.push_str(" align start"),
        None => {}
    }
    match settings.join {
        Some(Join::Mitre) => out.push_str(" join mitre"),
        Some(Join::Round) => out.push_str(" join round"),
        Some(Join::Bevel) => out.push_str(" join bevel"),
        None => {}
    }
    if let Some(r) = settings.mitre_limit {
        let _ = write!(out, " mitre-limit {r}");
    }
    match settings.scale_mode {
        Some(ScaleMode::Multiply) => out.push_str(" scale-mode multiply"),
        Some(ScaleMode::Override) => out.push_str(" scale-mode override"),
        None => {}
    }
}

fn write_curve(out: &mut String, curve: &SwpCurve, name: &str) {
    let keyword = curve.keyword();
    let dim = if curve.dim == 3 { 3 } else { 2 };
    let empty: &[DVec3] = &[];
    let points = curve.geometry.points();
    let tangents = match &curve.geometry {
        SwpGeometry::Hermite { tangents, .. } => Some(tangents.as_slice()),
        _ => None,
    };
    // `fmt::Write` for `String` never fails, so the results below are ignored.
    match (curve.kind, &curve.geometry) {
        (SwpCurveKind::Circle, geometry) => {
            let radius = match geometry {
                SwpGeometry::Circle { radius } => *radius,
                _ => 0.0,
            };
            let _ = writeln!(out, "circ {name} {} {radius}", curve.steps);
        }
        (SwpCurveKind::Helix, geometry) => {
            let (radius, pitch, turns) = match geometry {
                SwpGeometry::Helix { radius, pitch, turns } => (*radius, *pitch, *turns),
                _ => (0.0, 0.0, 0.0),
            };
            let _ = writeln!(out, "helix {name} {} {radius} {pitch} {turns}", curve.steps);
        }
        (SwpCurveKind::Trefoil, geometry) => {
            let size = match geometry {
                SwpGeometry::Trefoil { size } => *size,
                _ => 0.0,
            };
            let _ = writeln!(out, "trefoil {name} {} {size}", curve.steps);
        }
        (SwpCurveKind::Hermite, _) => {
            let tangents = tangents.unwrap_or(empty);
            let count = points.len().min(tangents.len());
            let _ = writeln!(out, "{keyword} {name} {} {count}{}", curve.steps, options(curve));
            for (p, t) in points.iter().zip(tangents) {
                write_point(out, *p, dim);
                out.push(' ');
                write_point(out, *t, dim);
                out.push('\n');
            }
        }
        (SwpCurveKind::KochanekBartels, geometry) => {
            let shape = match geometry {
                SwpGeometry::Tcb { shape, .. } => shape.as_slice(),
                _ => &[],
            };
            let count = points.len().min(shape.len());
            let _ = writeln!(out, "{keyword} {name} {} {count}{}", curve.steps, options(curve));
            for (p, s) in points.iter().zip(shape) {
                write_point(out, *p, dim);
                // the shape goes inside the brackets, after the coordinates
                out.pop();
                let _ = writeln!(out, " {} {} {}]", s.tension, s.continuity, s.bias);
            }
        }
        (SwpCurveKind::Nurbs { .. }, geometry) => {
            let weights = match geometry {
                SwpGeometry::Nurbs { weights, .. } => weights.as_slice(),
                _ => &[],
            };
            let count = points.len().min(weights.len());
            let _ = writeln!(out, "{keyword} {name} {} {count}{}", curve.steps, options(curve));
            for (p, w) in points.iter().zip(weights) {
                write_point(out, *p, dim);
                // the weight goes inside the brackets, after the coordinates
                out.pop();
                let _ = writeln!(out, " {w}]");
            }
        }
        _ => {
            let _ = writeln!(out, "{keyword} {name} {} {}{}", curve.steps, points.len(), options(curve));
            for p in points {
                write_point(out, *p, dim);
                out.push('\n');
            }
        }
    }
}

/// The option tokens of a curve, each preceded by a space; empty for the defaults.
fn options(curve: &SwpCurve) -> String {
    let mut options = String::new();
    if curve.closed {
        options.push_str(" closed");
    }
    if let SwpCurveKind::CatmullRom { alpha } = curve.kind {
        if alpha == 0.5 {
            options.push_str(" centripetal");
        } else if alpha == 1.0 {
            options.push_str(" chordal");
        } else if alpha != 0.0 {
            let _ = write!(options, " alpha {alpha}");
        }
    }
    if let SwpCurveKind::Nurbs { degree } = curve.kind {
        let _ = write!(options, " degree {degree}");
        if let SwpGeometry::Nurbs { knots: Some(knots), .. } = &curve.geometry {
            options.push_str(" knots");
            for k in knots {
                let _ = write!(options, " {k}");
            }
        }
    }
    options
}

fn write_point(out: &mut String, p: DVec3, dim: usize) {
    let _ = if dim == 3 { write!(out, "[{} {} {}]", p.x, p.y, p.z) } else { write!(out, "[{} {}]", p.x, p.y) };
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::swp::{SourcePos, SwpSurface};

    fn curve(name: Option<&str>, kind: SwpCurveKind, dim: u8, geometry: SwpGeometry) -> SwpCurve {
        SwpCurve {
            name: name.map(str::to_owned),
            kind,
            dim,
            steps: 10,
            closed: false,
            geometry,
            pos: SourcePos::default(),
        }
    }

    #[test]
    fn layout() {
        let doc = SwpDocument {
            curves: vec![
                curve(
                    Some("p"),
                    SwpCurveKind::Bezier,
                    2,
                    SwpGeometry::Points(vec![
                        DVec3::new(0.0, 0.5, 0.0),
                        DVec3::new(1.0, -2.0, 0.0),
                        DVec3::new(2.0, 1e-3, 0.0),
                        DVec3::new(3.0, 0.1 + 0.2, 0.0),
                    ]),
                ),
                curve(None, SwpCurveKind::Circle, 2, SwpGeometry::Circle { radius: 0.4 }),
            ],
            surfaces: vec![SwpSurface {
                name: None,
                kind: SwpSurfaceKind::GeneralizedCylinder { profile: 0, sweep: 1, scale: None, twist: None },
                settings: Default::default(),
                pos: SourcePos::default(),
            }],
        };
        assert_eq!(
            write(&doc),
            "bez2 p 10 4\n[0 0.5]\n[1 -2]\n[2 0.001]\n[3 0.30000000000000004]\n\n\
             circ _c1 10 0.4\n\n\
             gcyl . p _c1\n"
        );
    }

    #[test]
    fn generated_names_avoid_existing_ones() {
        let circle = |name: Option<&str>| curve(name, SwpCurveKind::Circle, 2, SwpGeometry::Circle { radius: 1.0 });
        let doc = SwpDocument {
            curves: vec![circle(Some("_c1")), circle(None), circle(Some("a b")), circle(Some("_c1"))],
            surfaces: vec![SwpSurface {
                name: Some("_c1_1".into()),
                kind: SwpSurfaceKind::GeneralizedCylinder { profile: 1, sweep: 7, scale: Some(2), twist: None },
                settings: Default::default(),
                pos: SourcePos::default(),
            }],
        };
        assert_eq!(
            write(&doc),
            "circ _c1 10 1\n\ncirc _c1_2 10 1\n\ncirc _c2 10 1\n\ncirc _c3 10 1\n\n\
             gcyl _c1_1 _c1_2 . scale _c2\n"
        );
    }

    #[test]
    fn primitives_and_clauses() {
        let doc = SwpDocument {
            curves: vec![
                curve(None, SwpCurveKind::Circle, 2, SwpGeometry::Circle { radius: 0.25 }),
                curve(None, SwpCurveKind::Helix, 3, SwpGeometry::Helix { radius: 1.5, pitch: -0.1, turns: 2.5 }),
                curve(Some("k"), SwpCurveKind::Trefoil, 3, SwpGeometry::Trefoil { size: 2.0 }),
                curve(Some("s"), SwpCurveKind::Circle, 2, SwpGeometry::Circle { radius: 1.0 }),
            ],
            surfaces: vec![SwpSurface {
                name: None,
                kind: SwpSurfaceKind::GeneralizedCylinder { profile: 0, sweep: 1, scale: Some(3), twist: Some(0) },
                settings: Default::default(),
                pos: SourcePos::default(),
            }],
        };
        assert_eq!(
            write(&doc),
            "circ _c0 10 0.25\n\nhelix _c1 10 1.5 -0.1 2.5\n\ntrefoil k 10 2\n\ncirc s 10 1\n\n\
             gcyl . _c0 _c1 scale s twist _c0\n"
        );
    }

    #[test]
    fn empty_document() {
        assert_eq!(write(&SwpDocument::default()), "");
    }
}
