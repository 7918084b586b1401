//! The subdivision schemes as one type, [`Scheme`]: what each takes and gives, which options
//! it has, and its names in messages, menus and on the command line. [`subdivide`](super::subdivide)
//! runs any of them.

use core::fmt;

use crate::mesh::PolyMesh;

/// A subdivision scheme. [`Scheme::ALL`] lists them all; the capability methods say what each
/// takes, carries and offers, so that a program can list, check and describe them without a
/// list of its own.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Scheme {
    /// Loop subdivision of triangle meshes ([`loop_subdivide`](super::loop_subdivide)), the
    /// default.
    #[default]
    Loop,
    /// Catmull-Clark subdivision of polygon meshes
    /// ([`catmull_clark_subdivide`](super::catmull_clark_subdivide)).
    CatmullClark,
    /// Kobbelt's √3 subdivision of triangle meshes ([`sqrt3_subdivide`](super::sqrt3_subdivide)).
    Sqrt3,
    /// Doo-Sabin subdivision of polygon meshes ([`doo_sabin_subdivide`](super::doo_sabin_subdivide)).
    DooSabin,
    /// The interpolating modified butterfly scheme on triangle meshes
    /// ([`butterfly_subdivide`](super::butterfly_subdivide)).
    Butterfly,
    /// Bilinear subdivision of polygon meshes ([`bilinear_subdivide`](super::bilinear_subdivide)).
    Bilinear,
}

/// Which of a mesh's attributes a scheme carries to the subdivided mesh (positions always).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct CarriedAttributes {
    /// Texture coordinates: where every vertex has one UV only, for √3 and butterfly.
    pub uvs: bool,
    /// Per-vertex colours.
    pub colors: bool,
    /// Face-varying normals.
    pub normals: bool,
}

impl Scheme {
    /// Every scheme, in the order of menus and `--help`.
    pub const ALL: [Self; 6] =
        [Self::Loop, Self::CatmullClark, Self::Sqrt3, Self::DooSabin, Self::Butterfly, Self::Bilinear];

    /// The scheme's name on the command line and in files: `loop`, `catmull-clark`, `sqrt3`,
    /// `doo-sabin`, `butterfly`, `bilinear`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Loop => "loop",
            Self::CatmullClark => "catmull-clark",
            Self::Sqrt3 => "sqrt3",
            Self::DooSabin => "doo-sabin",
            Self::Butterfly => "butterfly",
            Self::Bilinear => "bilinear",
        }
    }

    /// The scheme whose [`Self::name`] is `name`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The scheme's title in menus, capitalised: `Loop`, `Catmull-Clark`, `√3`, `Doo-Sabin`,
    /// `Butterfly`, `Bilinear`. In a sentence, use its [`Display`](fmt::Display) form.
    #[must_use]
    pub const fn title(self) -> &'static str {
        match self {
            Self::Butterfly => "Butterfly",
            Self::Bilinear => "Bilinear",
            _ => self.in_text(),
        }
    }

    /// The name inside a sentence ("{scheme} subdivision"): the names of people stay
    /// capitalised, the others do not.
    const fn in_text(self) -> &'static str {
        match self {
            Self::Loop => "Loop",
            Self::CatmullClark => "Catmull-Clark",
            Self::Sqrt3 => "√3",
            Self::DooSabin => "Doo-Sabin",
            Self::Butterfly => "butterfly",
            Self::Bilinear => "bilinear",
        }
    }

    /// One line on what the scheme takes and does, for `--help` and tooltips.
    #[must_use]
    pub const fn description(self) -> &'static str {
        match self {
            Self::Loop => "Loop (triangle meshes)",
            Self::CatmullClark => "Catmull-Clark (any polygon mesh; the result is all quads)",
            Self::Sqrt3 => "√3 (triangle meshes; CGAL's rules)",
            Self::DooSabin => "Doo-Sabin (any polygon mesh; CGAL's rules)",
            Self::Butterfly => "Modified butterfly (triangle meshes; interpolating; OpenMesh's rules)",
            Self::Bilinear => {
                "Bilinear (any polygon mesh: every n-gon into n quads at its centroid and edge midpoints, nothing \
                 moved; OpenSubdiv's rules)"
            }
        }
    }

    /// The library whose rules the scheme follows, to the bit: `OpenSubdiv`, `CGAL` or
    /// `OpenMesh`.
    #[must_use]
    pub const fn reference(self) -> &'static str {
        match self {
            Self::Loop | Self::CatmullClark | Self::Bilinear => "OpenSubdiv",
            Self::Sqrt3 | Self::DooSabin => "CGAL",
            Self::Butterfly => "OpenMesh",
        }
    }

    /// Whether the scheme takes triangle meshes only (refusing another face with
    /// [`SubdivError::NotTriangles`](super::SubdivError::NotTriangles)); the others take any
    /// polygon mesh.
    #[must_use]
    pub const fn triangles_only(self) -> bool {
        matches!(self, Self::Loop | Self::Sqrt3 | Self::Butterfly)
    }

    /// The faces of a subdivided mesh, in words: `triangles`, `quads` or (Doo-Sabin's
    /// polygons) `faces`.
    #[must_use]
    pub const fn faces_made(self) -> &'static str {
        match self {
            Self::Loop | Self::Sqrt3 | Self::Butterfly => "triangles",
            Self::CatmullClark | Self::Bilinear => "quads",
            Self::DooSabin => "faces",
        }
    }

    /// About how many faces each face becomes per level: 3 for √3, 4 for the others.
    #[must_use]
    pub const fn face_growth(self) -> u32 {
        if matches!(self, Self::Sqrt3) { 3 } else { 4 }
    }

    /// Whether the scheme has sharp and semi-sharp creases and a
    /// [`CreasingMethod`](super::CreasingMethod) (Loop and Catmull-Clark); the others ignore
    /// creases.
    #[must_use]
    pub const fn supports_creases(self) -> bool {
        matches!(self, Self::Loop | Self::CatmullClark)
    }

    /// Whether the scheme takes non-manifold meshes: Loop and Catmull-Clark with OpenSubdiv's
    /// rules (and degenerate faces too), bilinear, which moves nothing, as they are; √3,
    /// Doo-Sabin and butterfly refuse them.
    #[must_use]
    pub const fn takes_nonmanifold(self) -> bool {
        !matches!(self, Self::Sqrt3 | Self::DooSabin | Self::Butterfly)
    }

    /// Whether [`SubdivisionOptions::boundary`](super::SubdivisionOptions::boundary) and
    /// [`holes`](super::SubdivisionOptions::holes) apply (Loop and Catmull-Clark); the others
    /// have one boundary rule.
    #[must_use]
    pub const fn has_boundary_rule(self) -> bool {
        self.supports_creases()
    }

    /// Whether [`SubdivisionOptions::weights`](super::SubdivisionOptions::weights) applies
    /// (Loop's even-vertex weights).
    #[must_use]
    pub const fn has_weights(self) -> bool {
        matches!(self, Self::Loop)
    }

    /// Whether [`SubdivisionOptions::triangles`](super::SubdivisionOptions::triangles) applies
    /// (Catmull-Clark's edge points next to triangles).
    #[must_use]
    pub const fn has_triangle_rule(self) -> bool {
        matches!(self, Self::CatmullClark)
    }

    /// Whether limit positions and normals are computed ([`Subdivided::into_limit`](super::Subdivided::into_limit),
    /// exact masks: Loop and Catmull-Clark).
    #[must_use]
    pub const fn has_limit_positions(self) -> bool {
        self.supports_creases()
    }

    /// Whether the scheme is interpolating: the vertices of every level stay where they are
    /// (butterfly, bilinear), so they lie on the limit surface.
    #[must_use]
    pub const fn is_interpolating(self) -> bool {
        matches!(self, Self::Butterfly | Self::Bilinear)
    }

    /// Whether the scheme only splits the faces and moves nothing (bilinear): its surface is
    /// the polygons.
    #[must_use]
    pub const fn is_linear(self) -> bool {
        matches!(self, Self::Bilinear)
    }

    /// Whether [`SubdivisionOptions::color_by_level`](super::SubdivisionOptions::color_by_level)
    /// applies: every scheme but Doo-Sabin, which makes every vertex anew at every level.
    #[must_use]
    pub const fn colors_by_level(self) -> bool {
        !matches!(self, Self::DooSabin)
    }

    /// The attributes the scheme carries (on a manifold mesh).
    #[must_use]
    pub const fn carries(self) -> CarriedAttributes {
        let (uvs, normals) = match self {
            Self::Loop | Self::Bilinear => (true, true),
            Self::Sqrt3 | Self::DooSabin | Self::Butterfly => (true, false),
            Self::CatmullClark => (false, false),
        };
        CarriedAttributes { uvs, colors: true, normals }
    }

    /// A bound on the triangles (polygons fanned) of `levels` levels of the scheme on `mesh`:
    /// `F·4ᴺ` for Loop and butterfly, `F·3ᴺ` for √3, `C·4ᴺ/2` for Catmull-Clark and bilinear
    /// (`C·4ᴺ⁻¹` quads, `N ≥ 1`) and `C·4ᴺ` for Doo-Sabin (its corners at most quadruple per
    /// level, and a mesh of `C` corners has at most `C` triangles), `F` faces and `C` corners of
    /// `mesh`; without levels, the mesh's own. (`f64`, so that it cannot overflow.)
    #[must_use]
    pub fn max_triangles(self, mesh: &PolyMesh, levels: u32) -> f64 {
        let (faces, corners) = (mesh.num_faces() as f64, mesh.face_vertices.len() as f64);
        let n = i32::try_from(levels).unwrap_or(i32::MAX);
        if levels == 0 {
            return corners - 2.0 * faces;
        }
        match self {
            Self::Loop | Self::Butterfly => faces * 4f64.powi(n),
            Self::Sqrt3 => faces * 3f64.powi(n),
            Self::CatmullClark | Self::Bilinear => corners * 4f64.powi(n) / 2.0,
            Self::DooSabin => corners * 4f64.powi(n),
        }
    }
}

/// The name inside a sentence: `Loop`, `Catmull-Clark`, `√3`, `Doo-Sabin`, `butterfly`,
/// `bilinear` (see [`Scheme::title`] for menus).
impl fmt::Display for Scheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.in_text())
    }
}
