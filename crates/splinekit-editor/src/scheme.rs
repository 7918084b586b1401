//! The subdivision schemes the editor offers for a loaded mesh ([`Scheme`]), and how a level
//! of each is made from the one before.

use splinekit::PolyMesh;
use splinekit::subdiv::{
    ButterflyOptions, CatmullClarkOptions, Creases, CreasingMethod, DooSabinOptions, LoopOptions, Sqrt3Options,
    butterfly_step, catmull_clark_step, catmull_clark_subdivide_creased, doo_sabin_subdivide, loop_subdivide_creased,
    sqrt3_subdivide,
};
// for the link in `Scheme::polygon_level`'s docs
#[cfg(doc)]
use splinekit::subdiv::LoopPyramid;

/// The subdivision schemes the editor offers for a loaded mesh.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Scheme {
    /// Loop (triangle meshes).
    #[default]
    Loop,
    /// Catmull-Clark (any polygon mesh; quads after one level).
    CatmullClark,
    /// Kobbelt's √3 (triangle meshes; the boundary is refined every second level).
    Sqrt3,
    /// Doo-Sabin (any polygon mesh; a face per face, edge and vertex).
    DooSabin,
    /// Modified butterfly (triangle meshes; interpolating: vertices stay where they are).
    Butterfly,
}

impl Scheme {
    /// Every scheme, in the menu's order.
    pub const ALL: [Self; 5] = [Self::Loop, Self::CatmullClark, Self::Sqrt3, Self::DooSabin, Self::Butterfly];

    /// The name in the scheme menu.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Loop => "Loop",
            Self::CatmullClark => "Catmull-Clark",
            Self::Sqrt3 => "√3",
            Self::DooSabin => "Doo-Sabin",
            Self::Butterfly => "Butterfly",
        }
    }

    /// Whether the scheme has creases (Loop and Catmull-Clark).
    #[must_use]
    pub fn has_creases(self) -> bool {
        matches!(self, Self::Loop | Self::CatmullClark)
    }

    /// Level `depth` of `base` (`depth ≥ 1`) from level `depth − 1`, `coarse`, for the
    /// schemes other than Loop without creases (whose levels are a [`LoopPyramid`]). With
    /// `creases` (on `base`), Loop and Catmull-Clark make it from `base` with them (Chaikin's
    /// creasing, as OpenSubdiv's default in the command line).
    pub(crate) fn polygon_level(
        self,
        base: &PolyMesh,
        coarse: &PolyMesh,
        creases: &Creases,
        depth: usize,
        color_by_level: bool,
    ) -> Result<PolyMesh, String> {
        let method = CreasingMethod::Chaikin;
        match self {
            Self::Loop if !creases.is_empty() => {
                let options = LoopOptions { color_by_level, ..LoopOptions::default() };
                loop_subdivide_creased(base, depth as u32, &options, creases, method).map(|(fine, _)| fine)
            }
            Self::CatmullClark if !creases.is_empty() => {
                let options = CatmullClarkOptions { color_by_level, ..CatmullClarkOptions::default() };
                catmull_clark_subdivide_creased(base, depth, &options, creases, method).map(|(fine, _)| fine)
            }
            Self::Loop | Self::CatmullClark => {
                let options = CatmullClarkOptions { color_by_level, ..CatmullClarkOptions::default() };
                catmull_clark_step(coarse, depth, &options)
            }
            // From the loaded mesh: the boundary rule depends on the level's parity.
            Self::Sqrt3 => sqrt3_subdivide(base, depth, &Sqrt3Options { color_by_level }),
            Self::DooSabin => doo_sabin_subdivide(coarse, 1, &DooSabinOptions::default()),
            Self::Butterfly => butterfly_step(coarse, depth, &ButterflyOptions { color_by_level }),
        }
        .map_err(|e| e.to_string())
    }
}
