//! The 3D picture: a CPU rasterizer with a depth buffer ([`render_mesh`], [`render_scene`],
//! [`Renderer`]).
//!
//! # Method
//!
//! 1. A [`Camera`] frames every mesh vertex and mark ([`Camera::fit`]).
//! 2. **Visibility pass.** Triangles (the meshes', then screen-space triangles that draw the
//!    [`Mark`]s) are rasterized on a grid of `supersample × supersample` samples per pixel
//!    with exact integer edge functions (1/16-sample fixed point, top-left fill rule: a shared
//!    edge's samples belong to exactly one triangle, so no cracks or double hits) into a
//!    depth buffer and a buffer of triangle ids. The depth is the reciprocal distance
//!    (perspective) or minus the distance (orthographic), both linear in screen space. Mesh
//!    triangles keep the nearest sample; front faces (counter-clockwise as seen) are drawn
//!    first, then the others, each group in mesh order, and ties go to the earlier drawn.
//!    Before the second group, each 8×8 tile of samples notes its farthest depth, and a
//!    triangle whose nearest corner (with a bound on rounding) is no nearer than that in
//!    every tile it touches is skipped: on a closed surface most back faces are. Marks are
//!    drawn last, pulled towards the eye by a small bias so that curves lying on a surface
//!    show, and win ties (so a dot's fill covers its outline).
//! 3. **Shading pass.** Each pixel shades the triangles its samples saw and averages the
//!    colours in linear RGB (one shading when all its samples saw one triangle). Surfaces are
//!    lit as in the editor's 3D view: per-pixel Lambert from a key light above left of the
//!    eye, a fill light from the eye and a Blinn–Phong highlight, on whichever side is seen;
//!    normals are interpolated perspective-correctly. Front faces (counter-clockwise as seen,
//!    see [`TriMesh`]) take the front colour or the mesh's vertex colours, back faces the
//!    back colour. The wireframe overlay darkens pixels within half a line width of a
//!    triangle's own edges, so hidden lines stay hidden.
//! 4. **Colours** ([`RenderOptions::colour`], [`SurfaceColour`]): curvature and level
//!    colours replace the front colour per vertex (interpolated like the mesh's own vertex
//!    colours); the UV checker is evaluated per sample from perspective-correct UVs (each
//!    sample shaded on its own, so the squares' edges are anti-aliased too). Curvature and
//!    level pictures get a [`Legend`] in their bottom left corner.
//!
//! The picture is made in bands of 16 pixel rows: the triangles are first binned by band
//! (in parallel chunks, in drawing order), then each band is rasterized into a thread's own
//! small sample buffers (a few hundred kilobytes, so they stay in cache) and shaded right
//! away. Bands run in parallel (feature `parallel`); each draws its triangles in the same
//! order whatever the thread count, so the picture is the same, byte for byte, on every run.
//!
//! Cost: linear in the triangles and the samples. The `render` bench (a 100k-triangle torus
//! at 800×600, a 2-core machine) measured 19 ms with 2×2 samples on two threads (37 ms on
//! one) and 14 ms with one sample per pixel (28 ms on one); per-pixel shading takes about
//! half of it, rasterization a third.

use glam::{DVec2, DVec3, Vec3A};
use splinekit::TriMesh;
use splinekit::mesh::vertex_curvature;
use splinekit::subdiv::LEVEL_COLORS;

use crate::camera::{Camera, DEFAULT_MARGIN, EMPTY_BOX, Extent, Projection, View, bounds, box_radius, grow_box};
use crate::colour::{
    CHECKER_COLOURS, Curvature, MIN_RELATIVE_SCALE, SCALE_PERCENTILE, SurfaceColour, checker_parity, diverging_colour,
    symmetric_scale, to_unit,
};
use crate::image::{Image, ImageSize, Rgb};
use crate::legend::Legend;
use crate::marks::Mark;

/// Front faces (light grey-blue, as the editor).
pub const FRONT_COLOUR: Rgb = [168, 186, 214];
/// Back faces (orange-red, as the editor).
pub const BACK_COLOUR: Rgb = [226, 92, 48];
/// The wireframe overlay.
pub const WIRE_COLOUR: Rgb = [24, 26, 34];
/// The background of 3D pictures (as the editor's 3D view).
pub const BACKGROUND: Rgb = [44, 47, 54];
/// Width of the wireframe lines in pixels.
pub const WIRE_WIDTH: f64 = 1.0;
/// Samples per pixel side chosen by `supersample: 0` for pictures of at most
/// [`SUPERSAMPLE_MAX_PIXELS`] pixels (larger ones get 1).
pub const AUTO_SUPERSAMPLE: u32 = 2;
/// The largest picture (in pixels) that `supersample: 0` supersamples.
pub const SUPERSAMPLE_MAX_PIXELS: usize = 4096 * 2048;
/// Marks are pulled towards the eye by this fraction of the scene's radius.
pub const MARK_DEPTH_BIAS: f64 = 0.01;

/// Samples whose depths differ by at most this fraction are taken as one surface (see
/// `Frame::one_smooth_surface`).
const SAME_SURFACE_DEPTH: f32 = 2e-3;
/// Fixed-point sub-sample bits of the edge functions.
const SUB_BITS: u32 = 4;
const SUB: f32 = (1 << SUB_BITS) as f32;
/// Sample rows per band of the visibility pass.
const BAND_PIXEL_ROWS: usize = 16;
/// No triangle.
const NONE: u32 = u32::MAX;
/// The sample buffers' id of a mesh triangle seen from its back has this bit set (so the
/// shading pass tells front from back without looking the triangle up); ids themselves stay
/// below it.
const BACK: u32 = 1 << 31;
/// Unit direction towards the key light, in camera coordinates (x right, y up, z to the eye).
const LIGHT: Vec3A = Vec3A::new(-0.381_529, 0.599_546, 0.703_526);

/// How normals are chosen.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Shading {
    /// The mesh's vertex normals when it has them (one per vertex), else flat.
    #[default]
    Auto,
    /// The mesh's vertex normals, or area-weighted ones when it has none.
    Smooth,
    /// One normal per triangle.
    Flat,
}

/// How to draw a 3D picture.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct RenderOptions {
    /// Picture size.
    pub size: ImageSize,
    /// Direction to look from.
    pub view: View,
    /// Perspective or orthographic.
    pub projection: Projection,
    /// Free border, as a fraction of the smaller side ([`DEFAULT_MARGIN`]).
    pub margin: f64,
    /// Draw triangle edges over the surface (hidden ones stay hidden).
    pub wireframe: bool,
    /// Samples per pixel side (1 = no anti-aliasing, at most 4); 0 chooses
    /// [`AUTO_SUPERSAMPLE`].
    pub supersample: u32,
    /// Normals.
    pub shading: Shading,
    /// Background.
    pub background: Rgb,
    /// Front faces of meshes without vertex colours.
    pub front: Rgb,
    /// Back faces.
    pub back: Rgb,
    /// Wireframe lines.
    pub wire: Rgb,
    /// What colours the front of surfaces.
    pub colour: SurfaceColour,
    /// Draw the [`Legend`] of a curvature or level colouring into the picture.
    pub legend: bool,
}

impl RenderOptions {
    /// 800×600, iso view, perspective, no wireframe, 2×2 samples, the editor's colours,
    /// shaded surfaces ([`SurfaceColour::Shade`]), legends drawn.
    pub const DEFAULT: Self = Self {
        size: ImageSize::DEFAULT,
        view: View::Iso,
        projection: Projection::Perspective,
        margin: DEFAULT_MARGIN,
        wireframe: false,
        supersample: 0,
        shading: Shading::Auto,
        background: BACKGROUND,
        front: FRONT_COLOUR,
        back: BACK_COLOUR,
        wire: WIRE_COLOUR,
        colour: SurfaceColour::Shade,
        legend: true,
    };

    /// With this size.
    #[must_use]
    pub fn with_size(mut self, size: ImageSize) -> Self {
        self.size = size;
        self
    }

    /// With this view.
    #[must_use]
    pub fn with_view(mut self, view: View) -> Self {
        self.view = view;
        self
    }

    /// With this projection.
    #[must_use]
    pub fn with_projection(mut self, projection: Projection) -> Self {
        self.projection = projection;
        self
    }

    /// With or without the wireframe.
    #[must_use]
    pub fn with_wireframe(mut self, wireframe: bool) -> Self {
        self.wireframe = wireframe;
        self
    }

    /// With `n × n` samples per pixel (0: automatic).
    #[must_use]
    pub fn with_supersample(mut self, n: u32) -> Self {
        self.supersample = n;
        self
    }

    /// With this shading.
    #[must_use]
    pub fn with_shading(mut self, shading: Shading) -> Self {
        self.shading = shading;
        self
    }

    /// With this background.
    #[must_use]
    pub fn with_background(mut self, colour: Rgb) -> Self {
        self.background = colour;
        self
    }

    /// With this surface colouring.
    #[must_use]
    pub fn with_colour(mut self, colour: SurfaceColour) -> Self {
        self.colour = colour;
        self
    }

    /// With or without the legend of a colouring.
    #[must_use]
    pub fn with_legend(mut self, legend: bool) -> Self {
        self.legend = legend;
        self
    }

    /// Samples per pixel side actually used.
    #[must_use]
    pub fn samples_per_side(&self) -> u32 {
        match self.supersample {
            0 if self.size.num_pixels() <= SUPERSAMPLE_MAX_PIXELS => AUTO_SUPERSAMPLE,
            0 => 1,
            n => n.min(4),
        }
    }
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Meshes and marks to draw together.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// Shaded surfaces.
    pub meshes: Vec<TriMesh>,
    /// Lines, dots and arrows (drawn with depth, over surfaces they lie on).
    pub marks: Vec<Mark>,
}

/// Renders one mesh. See the [module docs](self).
#[must_use]
pub fn render_mesh(mesh: &TriMesh, options: &RenderOptions) -> Image {
    Renderer::new().render(&[mesh], &[], options)
}

/// Renders meshes and marks. See the [module docs](self).
#[must_use]
pub fn render_scene(scene: &Scene, options: &RenderOptions) -> Image {
    let meshes: Vec<&TriMesh> = scene.meshes.iter().collect();
    Renderer::new().render(&meshes, &scene.marks, options)
}

/// A rasterizer that keeps its buffers between pictures (for galleries and benchmarks).
#[derive(Debug, Default)]
pub struct Renderer {
    verts: Vec<Vert>,
    mark_tris: Vec<MarkTri>,
    /// Per chunk of triangles, per band, the chunk's triangles that may touch the band (see
    /// [`bin_triangles`]); kept between pictures so their memory is reused.
    bins: Vec<Vec<Vec<BinTri>>>,
}

/// A projected vertex: sample coordinates, depth key, 1/w, view-space position and normal.
#[derive(Clone, Copy, Debug, Default)]
struct Vert {
    x: f32,
    y: f32,
    z: f32,
    inv_w: f32,
    view: Vec3A,
    normal: Vec3A,
    /// Linear RGB front colour; for a mesh drawn with the UV checker, its UV `(u, v, 0)`.
    colour: Vec3A,
}

/// A screen-space triangle of a mark: sample coordinates and depth key per corner, and a
/// linear colour.
#[derive(Clone, Copy, Debug)]
struct MarkTri {
    v: [[f32; 3]; 3],
    colour: Vec3A,
}

/// What the shading pass needs to know about the frame.
struct Frame<'a> {
    meshes: &'a [&'a TriMesh],
    /// First global triangle id of each mesh, and one past the last.
    offsets: Vec<u32>,
    /// The first id of the marks (one past the meshes' last).
    last: u32,
    /// One mesh, shaded smoothly.
    one_smooth_mesh: bool,
    /// First vertex of each mesh in `verts`.
    vert_offsets: Vec<usize>,
    verts: &'a [Vert],
    mark_tris: &'a [MarkTri],
    smooth: Vec<bool>,
    /// Per mesh: drawn with the UV checker (its vertices carry UVs).
    checker: Vec<bool>,
    /// Shade every sample on its own (the UV checker).
    per_sample: bool,
    /// The checker's two colours, linear.
    checker_colours: [Vec3A; 2],
    perspective: bool,
    /// The Blinn–Phong half vector for the parallel projection's eye direction `+z`.
    half_ortho: Vec3A,
    ss: u32,
    sample_width: usize,
    back: Vec3A,
    background: Vec3A,
    wire: Option<(Vec3A, f32)>,
}

impl Renderer {
    /// A renderer with empty buffers.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Renders `meshes` and `marks`. See the [module docs](self).
    #[must_use]
    pub fn render(&mut self, meshes: &[&TriMesh], marks: &[Mark], options: &RenderOptions) -> Image {
        self.render_with_legend(meshes, marks, options).0
    }

    /// Renders `meshes` and `marks` as [`Self::render`] does, and says what the colours
    /// stand for: the [`Legend`] of a curvature or level colouring (drawn into the picture
    /// when [`RenderOptions::legend`] is set), `None` for the others.
    #[must_use]
    pub fn render_with_legend(
        &mut self,
        meshes: &[&TriMesh],
        marks: &[Mark],
        options: &RenderOptions,
    ) -> (Image, Option<Legend>) {
        let size = options.size;
        let ss = options.samples_per_side();
        let (sw, sh) = (size.width as usize * ss as usize, size.height as usize * ss as usize);
        // As `Camera::fit` on every vertex and mark point, the meshes' in parallel.
        let mark_points = || marks.iter().flat_map(Mark::points);
        let join = |a: (DVec3, DVec3), b: (DVec3, DVec3)| (a.0.min(b.0), a.1.max(b.1));
        let (lo, hi) = meshes
            .iter()
            .map(|m| par_fold(&m.positions, EMPTY_BOX, |b, &p| grow_box(b, p), join))
            .fold(bounds(mark_points()), join);
        let (camera, radius) = Camera::aimed(options.view, options.projection, lo, hi);
        let marks_extent = mark_points().fold(Extent::EMPTY, |e, p| camera.extend(e, p));
        let extent = meshes
            .iter()
            .map(|m| par_fold(&m.positions, Extent::EMPTY, |e, &p| camera.extend(e, p), Extent::union))
            .fold(marks_extent, Extent::union);
        let camera = camera.zoomed(extent, radius, size, options.margin);
        let radius = box_radius(lo, hi);

        // Vertices.
        let (coloured, legend) = surface_colours(meshes, options.colour, radius);
        let mut vert_offsets = Vec::with_capacity(meshes.len());
        let mut smooth = Vec::with_capacity(meshes.len());
        let mut checker = Vec::with_capacity(meshes.len());
        self.verts.clear();
        let front = linear_rgb(options.front);
        for (mesh, coloured) in meshes.iter().zip(&coloured) {
            vert_offsets.push(self.verts.len());
            let has_normals = mesh.normals.len() == mesh.positions.len();
            let use_smooth = match options.shading {
                Shading::Auto => has_normals,
                Shading::Smooth => true,
                Shading::Flat => false,
            };
            smooth.push(use_smooth);
            let computed;
            let normals: &[DVec3] = if use_smooth && !has_normals {
                computed = mesh.vertex_normal_sums();
                &computed
            } else if use_smooth {
                &mesh.normals
            } else {
                &[]
            };
            let n = mesh.positions.len();
            let attribute = match coloured {
                _ if options.colour == SurfaceColour::UvChecker && mesh.uvs.len() == n => Attribute::Uvs(&mesh.uvs),
                Some(colours) => Attribute::Colours(colours),
                None if mesh.colors.len() == n => Attribute::Colours(&mesh.colors),
                None => Attribute::Front(front),
            };
            checker.push(matches!(attribute, Attribute::Uvs(_)));
            project_vertices(&camera, ss, mesh, normals, attribute, &mut self.verts);
        }
        let mut offsets = Vec::with_capacity(meshes.len() + 1);
        let mut total = 0u64;
        for m in meshes {
            offsets.push(total as u32);
            total += m.triangles.len() as u64;
        }
        offsets.push(total as u32);
        // Ids must stay below BACK (meshes' triangles beyond are not drawn).
        let mark_base = total;

        // Marks as screen-space triangles.
        self.mark_tris.clear();
        for mark in marks {
            mark_triangles(mark, &camera, ss, MARK_DEPTH_BIAS * radius, &mut self.mark_tris);
        }
        let mark_count = self.mark_tris.len().min((u64::from(BACK) - mark_base.min(u64::from(BACK))) as usize);

        // Bands of pixel rows, each rasterized into its own small sample buffers and shaded
        // right away (the buffers stay in cache, and no frame-sized sample buffer is cleared).
        let band_rows = BAND_PIXEL_ROWS * ss as usize;
        bin_triangles(meshes, &vert_offsets, &self.verts, &self.mark_tris[..mark_count], sh, band_rows, &mut self.bins);
        let frame = Frame {
            meshes,
            last: *offsets.last().unwrap_or(&0),
            one_smooth_mesh: smooth == [true],
            offsets,
            vert_offsets,
            verts: &self.verts,
            mark_tris: &self.mark_tris,
            smooth,
            per_sample: checker.contains(&true),
            checker,
            checker_colours: CHECKER_COLOURS.map(linear_rgb),
            perspective: options.projection == Projection::Perspective,
            half_ortho: (LIGHT + Vec3A::Z).normalize(),
            ss,
            sample_width: sw,
            back: linear_rgb(options.back),
            background: linear_rgb(options.background),
            wire: options.wireframe.then(|| (linear_rgb(options.wire), (0.5 * WIRE_WIDTH) as f32)),
        };
        let lut = SrgbLut::new();
        let w = size.width as usize;
        let mut data = vec![0u8; 4 * size.num_pixels()];
        let bins = &self.bins;
        let band = |scratch: &mut BandBuffers, (b, out): (usize, &mut [u8])| {
            // Visibility pass.
            let (y0, y1) = (b * band_rows, ((b + 1) * band_rows).min(sh));
            let n = (y1 - y0) * sw;
            scratch.depth.clear();
            scratch.depth.resize(n, f32::NEG_INFINITY);
            scratch.ids.clear();
            scratch.ids.resize(n, NONE);
            let mut target = Band { depth: &mut scratch.depth, ids: &mut scratch.ids, width: sw, y0, y1 };
            // Front faces first; then, against the depth they leave, the others (each skipped
            // where it is certainly behind) and the marks.
            for part in bins {
                for t in &part[2 * b] {
                    target.triangle(t.v, t.id, false, None);
                }
            }
            // (Only when some mesh triangle could be skipped.)
            let tiles = bins.iter().any(|part| part[2 * b + 1].iter().any(|t| u64::from(t.id) < mark_base));
            if tiles {
                target.farthest_per_tile(&mut scratch.tiles);
            }
            for part in bins {
                for t in &part[2 * b + 1] {
                    let mark = u64::from(t.id) >= mark_base;
                    target.triangle(t.v, t.id, mark, (tiles && !mark).then_some(&scratch.tiles[..]));
                }
            }
            // Shading pass.
            let (ids, depth, row) = (&scratch.ids[..], &scratch.depth[..], &mut scratch.row);
            for (r, out) in out.chunks_mut(4 * w).enumerate() {
                let py = b * BAND_PIXEL_ROWS + r;
                match ss {
                    1 => frame.shade_row::<1>(r, py, ids, depth, &lut, row, out),
                    2 => frame.shade_row::<2>(r, py, ids, depth, &lut, row, out),
                    3 => frame.shade_row::<3>(r, py, ids, depth, &lut, row, out),
                    _ => frame.shade_row::<4>(r, py, ids, depth, &lut, row, out),
                }
            }
        };
        let bands = data.chunks_mut(4 * w * BAND_PIXEL_ROWS).enumerate();
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            let bands: Vec<_> = bands.collect();
            bands.into_par_iter().for_each_init(BandBuffers::default, band);
        }
        #[cfg(not(feature = "parallel"))]
        {
            let mut scratch = BandBuffers::default();
            bands.for_each(|b| band(&mut scratch, b));
        }
        let mut image = Image::from_rgba(size.width, size.height, data).expect("the buffer has the image's size");
        if let (Some(legend), true) = (&legend, options.legend) {
            legend.draw(&mut image);
        }
        (image, legend)
    }
}

/// Per mesh, the vertex colours (sRGB in `[0, 1]`) that `colour` gives it instead of its
/// own (`None`: its own, or the front colour), and the legend; `radius` is the scene's. The
/// editor colours its 3D view with the same map and scale.
#[must_use]
pub fn surface_colours(
    meshes: &[&TriMesh],
    colour: SurfaceColour,
    radius: f64,
) -> (Vec<Option<Vec<DVec3>>>, Option<Legend>) {
    match colour {
        SurfaceColour::Curvature(curvature) => {
            let values: Vec<Vec<f64>> = meshes
                .iter()
                .map(|m| {
                    let c = vertex_curvature(m);
                    match curvature {
                        Curvature::Mean => c.mean,
                        Curvature::Gaussian => c.gauss,
                    }
                })
                .collect();
            let floor = MIN_RELATIVE_SCALE / radius.powi(curvature.inverse_length_power());
            let scale = symmetric_scale(values.iter().flatten().copied(), SCALE_PERCENTILE, floor);
            let t = |x: f64| if scale > 0.0 { x / scale } else { 0.0 };
            let colours = values.iter().map(|v| Some(v.iter().map(|&x| to_unit(diverging_colour(t(x)))).collect()));
            let (min, max) = values
                .iter()
                .flatten()
                .filter(|v| v.is_finite())
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)));
            let (min, max) = if min <= max { (min, max) } else { (0.0, 0.0) };
            (colours.collect(), Some(Legend::Curvature { curvature, scale, min, max }))
        }
        SurfaceColour::Level { levels } => {
            // At level 0 every vertex is level 0, whatever colours the mesh has.
            let n = |m: &TriMesh| m.positions.len();
            let base = |m: &TriMesh| (levels == 0 || m.colors.len() != n(m)).then(|| vec![LEVEL_COLORS[0]; n(m)]);
            (meshes.iter().map(|m| base(m)).collect(), Some(Legend::Levels { levels }))
        }
        SurfaceColour::Shade | SurfaceColour::UvChecker => (vec![None; meshes.len()], None),
    }
}

/// What a mesh's projected vertices carry in [`Vert::colour`].
#[derive(Clone, Copy)]
enum Attribute<'a> {
    /// One colour for all (linear).
    Front(Vec3A),
    /// A colour per vertex (sRGB in `[0, 1]`).
    Colours(&'a [DVec3]),
    /// A UV per vertex (the UV checker).
    Uvs(&'a [DVec2]),
}

/// `items` folded with `fold` from `init` (in parallel chunks for large inputs, the
/// results joined with `join`, which must be associative for the result not to depend on
/// the thread count; the bounds and extents here are exact minima and maxima).
fn par_fold<T: Sync, A: Copy + Send + Sync>(
    items: &[T],
    init: A,
    fold: impl Fn(A, &T) -> A + Sync + Send,
    join: impl Fn(A, A) -> A + Sync + Send,
) -> A {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        items.par_chunks(1 << 12).map(|c| c.iter().fold(init, &fold)).reduce(|| init, &join)
    }
    #[cfg(not(feature = "parallel"))]
    {
        let _ = &join;
        items.iter().fold(init, fold)
    }
}

/// Projects `mesh`'s vertices into `out`.
fn project_vertices(
    camera: &Camera,
    ss: u32,
    mesh: &TriMesh,
    normals: &[DVec3],
    attribute: Attribute<'_>,
    out: &mut Vec<Vert>,
) {
    let ss = f64::from(ss);
    let perspective = camera.projection == Projection::Perspective;
    let project = |(i, &p): (usize, &DVec3)| {
        let q = camera.project(p);
        let valid = p.is_finite() && (!perspective || q.depth > 0.0);
        let (z, inv_w) = match camera.projection {
            Projection::Perspective => (1.0 / q.depth, 1.0 / q.depth),
            Projection::Orthographic => (-q.depth, 1.0),
        };
        let normal = normals.get(i).map_or(Vec3A::ZERO, |&n| camera.dir_to_view(n).as_vec3a().normalize_or_zero());
        let colour = match attribute {
            Attribute::Front(front) => front,
            Attribute::Colours(c) => {
                let c = c[i];
                Vec3A::new(srgb_to_linear(c.x as f32), srgb_to_linear(c.y as f32), srgb_to_linear(c.z as f32))
            }
            Attribute::Uvs(uv) => Vec3A::new(uv[i].x as f32, uv[i].y as f32, 0.0),
        };
        Vert {
            x: if valid { (q.x * ss) as f32 } else { f32::NAN },
            y: (q.y * ss) as f32,
            z: z as f32,
            inv_w: inv_w as f32,
            view: camera.to_view(p).as_vec3a(),
            normal,
            colour,
        }
    };
    // In parallel for large meshes (the order, hence the picture, is the same).
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        out.par_extend(mesh.positions.par_iter().enumerate().with_min_len(1 << 12).map(project));
    }
    #[cfg(not(feature = "parallel"))]
    out.extend(mesh.positions.iter().enumerate().map(project));
}

/// A triangle to rasterize: sample coordinates and depth key per corner, and global id.
#[derive(Clone, Copy, Debug)]
struct BinTri {
    v: [[f32; 3]; 3],
    id: u32,
}

/// Triangles binned per pass of [`bin_triangles`]: large enough to amortize a pass's bins,
/// small enough to share the work among threads.
const BIN_CHUNK: usize = 1 << 14;

/// Bins the triangles into `bins[chunk][band]`: for each chunk of triangles (in drawing
/// order) and each band of sample rows, the chunk's triangles that may touch the band, with
/// their corners copied in. A band then reads its triangles in order (chunk by chunk) from a
/// few arrays instead of gathering corners from the vertex array at random. Chunks are
/// binned in parallel, and a band reads the chunks in order, so the drawing order is the
/// same on any number of threads. The vectors are reused: after the first picture of a
/// size, binning allocates nothing.
fn bin_triangles(
    meshes: &[&TriMesh],
    vert_offsets: &[usize],
    verts: &[Vert],
    mark_tris: &[MarkTri],
    rows: usize,
    band_rows: usize,
    bins: &mut Vec<Vec<Vec<BinTri>>>,
) {
    let num_bands = rows.div_ceil(band_rows);
    // Chunks: (mesh, first triangle, end, global id of the first); `usize::MAX` for the marks.
    let mut chunks = Vec::new();
    let mut id = 0u32;
    for (mi, mesh) in meshes.iter().enumerate() {
        let n = mesh.triangles.len();
        for start in (0..n).step_by(BIN_CHUNK) {
            chunks.push((mi, start, (start + BIN_CHUNK).min(n), id + start as u32));
        }
        id += n as u32;
    }
    chunks.push((usize::MAX, 0, mark_tris.len(), id));
    bins.resize_with(chunks.len(), Vec::new);
    let bin_chunk = |(bins, &(mi, start, end, first)): (&mut Vec<Vec<BinTri>>, &(usize, usize, usize, u32))| {
        bins.resize_with(2 * num_bands, Vec::new);
        bins.iter_mut().for_each(Vec::clear);
        // Front faces (counter-clockwise as seen: negative area, y down) in the band's first
        // list, the others and marks in its second.
        let mut add = |v: [[f32; 3]; 3], id: u32, front: bool| {
            let ys = [v[0][1], v[1][1], v[2][1]];
            let lo = ys[0].min(ys[1]).min(ys[2]);
            let hi = ys[0].max(ys[1]).max(ys[2]);
            // NaN fails both tests.
            if !(hi >= 0.0 && lo < rows as f32) || id >= BACK {
                return;
            }
            let b0 = (lo.max(0.0) as usize) / band_rows;
            let b1 = ((hi as usize) / band_rows).min(num_bands - 1);
            for band in b0..=b1 {
                bins[2 * band + usize::from(!front)].push(BinTri { v, id });
            }
        };
        if mi == usize::MAX {
            for (k, m) in mark_tris.iter().enumerate() {
                add(m.v, first + k as u32, false);
            }
            return;
        }
        let (mesh, vo) = (meshes[mi], vert_offsets[mi]);
        let n = mesh.positions.len();
        for (k, t) in mesh.triangles[start..end].iter().enumerate() {
            // Out-of-range indices and unprojectable corners leave the triangle out.
            if t.iter().all(|&i| (i as usize) < n) {
                let v = t.map(|i| {
                    let p = &verts[vo + i as usize];
                    [p.x, p.y, p.z]
                });
                if !v.iter().any(|p| p[0].is_nan() || p[1].is_nan()) {
                    let area = (v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[1][1] - v[0][1]) * (v[2][0] - v[0][0]);
                    add(v, first + k as u32, area < 0.0);
                }
            }
        }
    };
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        bins.par_iter_mut().zip(chunks.par_iter()).for_each(bin_chunk);
    }
    #[cfg(not(feature = "parallel"))]
    bins.iter_mut().zip(chunks.iter()).for_each(bin_chunk);
}

/// One thread's sample buffers for a band: depth key and triangle id per sample, and the
/// shading pass's lists for a row.
#[derive(Default)]
struct BandBuffers {
    depth: Vec<f32>,
    ids: Vec<u32>,
    /// The farthest depth key per tile (see [`Band::farthest_per_tile`]).
    tiles: Vec<f32>,
    row: RowScratch,
}

/// What a row of pixels needs shaded, and its colours.
#[derive(Default)]
struct RowScratch {
    requests: Vec<Request>,
    /// Linear colour per pixel.
    colours: Vec<Vec3A>,
}

/// One shading: triangle `id` at sample position `(x, y)`, adding `weight` of its colour to
/// pixel `pixel` of the row.
struct Request {
    id: u32,
    x: f32,
    y: f32,
    weight: f32,
    pixel: u32,
}

/// The sample buffers of the band of sample rows `y0..y1` (row `y0` first).
struct Band<'a> {
    depth: &'a mut [f32],
    ids: &'a mut [u32],
    width: usize,
    y0: usize,
    y1: usize,
}

/// Side of the square tiles of samples whose farthest depth lets the second pass skip
/// hidden triangles.
const TILE: usize = 8;

impl Band<'_> {
    /// The smallest (farthest) depth key of each `TILE × TILE` tile of samples into `tiles`,
    /// row-major, `⌈width / TILE⌉` tiles per row (`-∞` where a sample is empty).
    fn farthest_per_tile(&self, tiles: &mut Vec<f32>) {
        let across = self.width.div_ceil(TILE);
        tiles.clear();
        for rows in self.depth.chunks(TILE * self.width) {
            let start = tiles.len();
            tiles.resize(start + across, f32::INFINITY);
            for row in rows.chunks_exact(self.width) {
                for (t, d) in tiles[start..].iter_mut().zip(row.chunks(TILE)) {
                    *t = d.iter().fold(*t, |m, &d| m.min(d));
                }
            }
        }
    }

    /// Rasterizes one triangle (sample coordinates and depth key per corner). `ties` (a
    /// mark) lets it win equal depths; otherwise (a mesh triangle) its id is stored with
    /// [`BACK`] when it is seen from its back (clockwise on screen).
    ///
    /// With `tiles` ([`Self::farthest_per_tile`], and the triangle drawn without `ties`),
    /// a triangle that is certainly behind every sample of the tiles its box touches is
    /// skipped (it would change nothing): its nearest corner, plus a bound on the rounding
    /// of the sample depths, is no nearer than the tiles' farthest depth.
    /// Returns whether the tile test skipped it.
    fn triangle(&mut self, v: [[f32; 3]; 3], id: u32, ties: bool, tiles: Option<&[f32]>) -> bool {
        const LIMIT: f32 = (1 << 26) as f32;
        let mut fx = [0i64; 3];
        let mut fy = [0i64; 3];
        for k in 0..3 {
            let (x, y) = (v[k][0] * SUB, v[k][1] * SUB);
            // NaN fails too.
            if !(x.abs() < LIMIT && y.abs() < LIMIT && v[k][2].is_finite()) {
                return false;
            }
            // Round half away from zero (cheaper than `round`, which may be a library call).
            fx[k] = (x + 0.5f32.copysign(x)) as i64;
            fy[k] = (y + 0.5f32.copysign(y)) as i64;
        }
        let mut area = (fx[1] - fx[0]) * (fy[2] - fy[0]) - (fy[1] - fy[0]) * (fx[2] - fx[0]);
        let mut order = [0, 1, 2];
        if area == 0 {
            return false;
        }
        // The screen's y points down: counter-clockwise as seen has a negative area.
        let id = if area > 0 && !ties { id | BACK } else { id };
        if area < 0 {
            order = [0, 2, 1];
            area = -area;
        }
        let (x, y, z) = (order.map(|k| fx[k]), order.map(|k| fy[k]), order.map(|k| v[k][2]));
        let half = 1i64 << (SUB_BITS - 1);
        let min_x = ((x[0].min(x[1]).min(x[2]) - half).max(0) >> SUB_BITS) as usize;
        let max_x = ((x[0].max(x[1]).max(x[2]) - half) >> SUB_BITS).min(self.width as i64 - 1);
        let min_y = (((y[0].min(y[1]).min(y[2]) - half).max(0) >> SUB_BITS) as usize).max(self.y0);
        let max_y = ((y[0].max(y[1]).max(y[2]) - half) >> SUB_BITS).min(self.y1 as i64 - 1);
        if max_x < min_x as i64 || max_y < min_y as i64 {
            return false;
        }
        let (max_x, max_y) = (max_x as usize, max_y as usize);
        // Edge k runs from corner k+1 to corner k+2, opposite corner k; e_k ≥ 0 inside.
        let mut a = [0i64; 3];
        let mut b = [0i64; 3];
        let mut c = [0i64; 3];
        for k in 0..3 {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            let (dx, dy) = (x[j] - x[i], y[j] - y[i]);
            // e(p) = dx·(py − yi) − dy·(px − xi) = a·px + b·py + c
            a[k] = -dy;
            b[k] = dx;
            c[k] = dy * x[i] - dx * y[i];
            // Top-left rule: inclusive edges keep e ≥ 0, the others need e > 0.
            let inclusive = dy > 0 || (dy == 0 && dx < 0);
            if !inclusive {
                c[k] -= 1;
            }
        }
        // The depth plane from the barycentric weights e_k / area, at the box's first sample
        // and per sample step in x and y. A flat depth (dots, marks seen face on) stays
        // exact, so later marks win its ties.
        let step = 1i64 << SUB_BITS;
        let (px0, py0) = ((min_x as i64) * step + half, (min_y as i64) * step + half);
        let e0 = [0, 1, 2].map(|k| a[k] * px0 + b[k] * py0 + c[k]);
        let (sa, sb) = (a.map(|a| a * step), b.map(|b| b * step));
        let (z0, dzdx, dzdy) = if z[0] == z[1] && z[1] == z[2] {
            (f64::from(z[0]), 0.0, 0.0)
        } else {
            let plane = |w: [i64; 3]| {
                (w[0] as f64 * f64::from(z[0]) + w[1] as f64 * f64::from(z[1]) + w[2] as f64 * f64::from(z[2]))
                    / area as f64
            };
            (plane(e0), plane(sa), plane(sb))
        };
        if let Some(tiles) = tiles {
            // Sample depths are convex combinations of the corners' computed with a few
            // roundings of terms no larger than these: 1e-5 of them bounds the error.
            let (w, h) = ((max_x - min_x) as f64, (max_y - min_y) as f64);
            let slack = 1e-5 * (z0.abs() + dzdx.abs() * w + dzdy.abs() * h);
            let nearest = f64::from(z[0].max(z[1]).max(z[2])) + slack;
            let across = self.width.div_ceil(TILE);
            let (tx0, tx1) = (min_x / TILE, max_x / TILE);
            let hidden = ((min_y - self.y0) / TILE..=(max_y - self.y0) / TILE)
                .all(|ty| tiles[ty * across + tx0..=ty * across + tx1].iter().all(|&t| f64::from(t) >= nearest));
            if hidden {
                return true;
            }
        }
        let dzdx = dzdx as f32;
        let mut e_row = e0;
        for (j, sy) in (min_y..=max_y).enumerate() {
            let e = e_row;
            for k in 0..3 {
                e_row[k] += sb[k];
            }
            // The row's span lo..=hi (offsets from min_x): e_k + i·sa_k ≥ 0 for each edge,
            // solved exactly in integers (numerators and divisors non-negative).
            let (mut lo, mut hi) = (0i64, (max_x - min_x) as i64);
            for k in 0..3 {
                let (e0, s) = (e[k], sa[k]);
                if s > 0 {
                    if e0 < 0 {
                        lo = lo.max((s - 1 - e0) / s);
                    }
                } else if e0 < 0 {
                    hi = -1;
                } else if s < 0 {
                    hi = hi.min(e0 / -s);
                }
            }
            if lo > hi {
                continue;
            }
            // Sample i of the row (from min_x) has depth z_row + i·dzdx.
            let z_row = (z0 + j as f64 * dzdy) as f32;
            let at = (sy - self.y0) * self.width + min_x;
            let span = lo as usize..=hi as usize;
            let (depth, ids) = (&mut self.depth[at..][span.clone()], &mut self.ids[at..][span]);
            if ties {
                span_keep::<true>(depth, ids, lo as usize, z_row, dzdx, id);
            } else {
                span_keep::<false>(depth, ids, lo as usize, z_row, dzdx, id);
            }
        }
        false
    }
}

/// Depth test of a row's covered span, which starts `lo` samples into a row whose first
/// sample has depth `z_row`.
#[inline(always)]
fn span_keep<const TIES: bool>(depth: &mut [f32], ids: &mut [u32], lo: usize, z_row: f32, dzdx: f32, id: u32) {
    for (i, (d, t)) in (lo..).zip(depth.iter_mut().zip(ids.iter_mut())) {
        let z = z_row + i as f32 * dzdx;
        let win = z > *d || (TIES && z == *d);
        *d = if win { z } else { *d };
        *t = if win { id } else { *t };
    }
}

impl Frame<'_> {
    /// Shades pixel row `py` (RGBA into `out`) from the `SS × SS` samples of each pixel, its
    /// row `r` of the band whose sample buffers are `ids` and `depth`. First each pixel
    /// says what it needs shaded (and with which weight) into `scratch`, then those shadings
    /// run in one loop whose branches are predictable, and the colours are encoded.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn shade_row<const SS: usize>(
        &self,
        r: usize,
        py: usize,
        ids: &[u32],
        depth: &[f32],
        lut: &SrgbLut,
        scratch: &mut RowScratch,
        out: &mut [u8],
    ) {
        let sw = self.sample_width;
        let w = out.len() / 4;
        let RowScratch { requests, colours } = scratch;
        requests.clear();
        colours.clear();
        colours.resize(w, Vec3A::ZERO);
        let rows: [&[u32]; SS] = std::array::from_fn(|sy| &ids[(r * SS + sy) * sw..(r * SS + sy + 1) * sw]);
        for (px, colour) in colours.iter_mut().enumerate() {
            let mut grid = [[NONE; SS]; SS];
            for sy in 0..SS {
                grid[sy].copy_from_slice(&rows[sy][px * SS..(px + 1) * SS]);
            }
            let samples = grid.as_flattened();
            let first = samples[0];
            if self.per_sample {
                // Every sample on its own, at its centre.
                let weight = 1.0 / (SS * SS) as f32;
                for (j, &id) in samples.iter().enumerate() {
                    if let Some(c) = self.plain_colour(id) {
                        *colour += c * weight;
                    } else {
                        let (x, y) = ((px * SS + j % SS) as f32 + 0.5, (py * SS + j / SS) as f32 + 0.5);
                        requests.push(Request { id, x, y, weight, pixel: px as u32 });
                    }
                }
                continue;
            }
            if samples.iter().all(|&s| s == first) || self.one_smooth_surface::<SS>(samples, depth, (px, r)) {
                if let Some(c) = self.plain_colour(first) {
                    *colour = c;
                } else {
                    let (x, y) = Self::centre::<SS>(px, py);
                    requests.push(Request { id: first, x, y, weight: 1.0, pixel: px as u32 });
                }
                continue;
            }
            // Each triangle seen once, at its first sample, weighted by its samples.
            for (j, &id) in samples.iter().enumerate() {
                if samples[..j].contains(&id) {
                    continue;
                }
                let weight = samples[j..].iter().filter(|&&s| s == id).count() as f32 / (SS * SS) as f32;
                if let Some(c) = self.plain_colour(id) {
                    *colour += c * weight;
                } else {
                    let (x, y) = ((px * SS + j % SS) as f32 + 0.5, (py * SS + j / SS) as f32 + 0.5);
                    requests.push(Request { id, x, y, weight, pixel: px as u32 });
                }
            }
        }
        for q in requests.iter() {
            colours[q.pixel as usize] += self.shade(q.id, (q.x, q.y)) * q.weight;
        }
        for (c, out) in colours.iter().zip(out.chunks_exact_mut(4)) {
            out.copy_from_slice(&[lut.encode(c.x), lut.encode(c.y), lut.encode(c.z), 255]);
        }
    }

    /// The centre of pixel `(px, py)` in sample coordinates.
    #[inline(always)]
    fn centre<const SS: usize>(px: usize, py: usize) -> (f32, f32) {
        ((px * SS) as f32 + 0.5 * SS as f32, (py * SS) as f32 + 0.5 * SS as f32)
    }

    /// Whether the samples of pixel `(px, py)` (`py` the pixel row in `depth`'s band) all see
    /// one smoothly shaded surface: mesh
    /// triangles of one smooth mesh, all facing the same way, at nearly the same depth. Such
    /// a pixel is shaded once, at its centre (its colour varies smoothly across it); the
    /// others (silhouettes, creases of flat shading, front/back borders, marks) once per
    /// triangle.
    #[inline(always)]
    fn one_smooth_surface<const SS: usize>(&self, ids: &[u32], depth: &[f32], (px, py): (usize, usize)) -> bool {
        // (Bitwise `|` and `&`: no branch per sample.)
        let other = ids.iter().fold(false, |o, &id| o | (id & !BACK >= self.last) | ((id ^ ids[0]) & BACK != 0));
        if !self.one_smooth_mesh || other {
            return false;
        }
        let width = self.sample_width;
        let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
        for sy in 0..SS {
            let base = (py * SS + sy) * width + px * SS;
            for &d in &depth[base..base + SS] {
                lo = if d < lo { d } else { lo };
                hi = if d > hi { d } else { hi };
            }
        }
        hi - lo <= SAME_SURFACE_DEPTH * hi.abs().max(lo.abs())
    }

    /// The colour of sample id `id` when it needs no shading: the background, or a mark's
    /// colour.
    #[inline]
    fn plain_colour(&self, id: u32) -> Option<Vec3A> {
        if id == NONE {
            Some(self.background)
        } else if id & !BACK >= self.last {
            Some(self.mark_tris[(id - self.last) as usize].colour)
        } else {
            None
        }
    }

    /// The mesh of mesh triangle `id` (without [`BACK`]) and its corners.
    #[inline(always)]
    fn corners(&self, id: u32) -> (usize, [&Vert; 3]) {
        let mi = if self.meshes.len() == 1 { 0 } else { self.offsets.partition_point(|&o| o <= id) - 1 };
        let t = self.meshes[mi].triangles[(id - self.offsets[mi]) as usize];
        let vo = self.vert_offsets[mi];
        (mi, t.map(|i| &self.verts[vo + i as usize]))
    }

    /// Linear colour of mesh triangle `id` (with or without [`BACK`]) at sample position
    /// `p`.
    fn shade(&self, id: u32, p: (f32, f32)) -> Vec3A {
        let (mi, v) = self.corners(id & !BACK);
        // Screen-space barycentrics (signed areas; `area` < 0 is counter-clockwise as seen,
        // the screen's y pointing down).
        let edge = |a: &Vert, b: &Vert| (b.x - a.x) * (p.1 - a.y) - (b.y - a.y) * (p.0 - a.x);
        let w = [edge(v[1], v[2]), edge(v[2], v[0]), edge(v[0], v[1])];
        let area = w[0] + w[1] + w[2];
        if area == 0.0 || !area.is_finite() {
            return self.background;
        }
        let front_facing = area < 0.0;
        // Perspective-correct weights: the screen weights w/area times 1/w, normalized (the
        // 1/area cancels).
        let pw = [w[0] * v[0].inv_w, w[1] * v[1].inv_w, w[2] * v[2].inv_w];
        let inv_sum = 1.0 / (pw[0] + pw[1] + pw[2]);
        let m = if inv_sum.is_finite() { [pw[0] * inv_sum, pw[1] * inv_sum, pw[2] * inv_sum] } else { [1.0 / 3.0; 3] };
        let pos = v[0].view * m[0] + v[1].view * m[1] + v[2].view * m[2];
        let to_eye = if self.perspective { (-pos).normalize_or(Vec3A::Z) } else { Vec3A::Z };
        // The geometric normal, turned to the eye: whichever side is seen is lit. A smooth
        // normal is turned to the same side (only the signs matter there, so the geometric
        // normal is normalized only when it is the one used).
        let mut ng = (v[1].view - v[0].view).cross(v[2].view - v[0].view);
        let len2 = ng.length_squared();
        if !(len2 > 0.0 && len2.is_finite()) {
            ng = to_eye;
        }
        if ng.dot(to_eye) < 0.0 {
            ng = -ng;
        }
        let smooth = if self.smooth[mi] {
            (v[0].normal * m[0] + v[1].normal * m[1] + v[2].normal * m[2]).try_normalize()
        } else {
            None
        };
        let n = match smooth {
            Some(s) if s.dot(ng) < 0.0 => -s,
            Some(s) => s,
            None => ng.normalize_or(to_eye),
        };
        let base = if !front_facing {
            self.back
        } else if self.per_sample && self.checker[mi] {
            let uv = v[0].colour * m[0] + v[1].colour * m[1] + v[2].colour * m[2];
            self.checker_colours[checker_parity(uv.x, uv.y)]
        } else {
            v[0].colour * m[0] + v[1].colour * m[1] + v[2].colour * m[2]
        };
        let diffuse = n.dot(LIGHT).max(0.0);
        let h = if self.perspective { (LIGHT + to_eye).normalize_or(Vec3A::Z) } else { self.half_ortho };
        let x = n.dot(h).max(0.0);
        let x2 = x * x;
        let x8 = (x2 * x2) * (x2 * x2);
        let x32 = (x8 * x8) * (x8 * x8);
        let specular = 0.2 * x32 * x8;
        let fill = 0.25 * n.dot(to_eye).max(0.0);
        let mut c = base * (0.12 + 0.7 * diffuse + fill) + Vec3A::splat(specular);
        if let Some((wire, half_width)) = self.wire {
            // Distance to the nearest edge of this triangle, in pixels.
            let len = |a: &Vert, b: &Vert| ((b.x - a.x).powi(2) + (b.y - a.y).powi(2)).sqrt();
            let lens = [len(v[1], v[2]), len(v[2], v[0]), len(v[0], v[1])];
            let mut d = f32::INFINITY;
            for k in 0..3 {
                if lens[k] > 0.0 {
                    d = d.min(w[k].abs() / lens[k]);
                }
            }
            let d = d / self.ss as f32;
            let t = (d - (half_width - 0.5)).clamp(0.0, 1.0);
            let edge = 1.0 - t * t * (3.0 - 2.0 * t);
            c = c + (wire - c) * edge;
        }
        c
    }
}

/// Screen-space triangles that draw `mark`, pulled towards the eye by `bias` world units.
fn mark_triangles(mark: &Mark, camera: &Camera, ss: u32, bias: f64, out: &mut Vec<MarkTri>) {
    let s = f64::from(ss);
    let project = |p: DVec3| -> Option<[f64; 3]> {
        let toward = match camera.projection {
            Projection::Perspective => (camera.eye - p).normalize_or(camera.back),
            Projection::Orthographic => camera.back,
        };
        let q = camera.project(p + toward * bias);
        if !p.is_finite() || q.depth <= 0.0 && camera.projection == Projection::Perspective {
            return None;
        }
        let z = match camera.projection {
            Projection::Perspective => 1.0 / q.depth,
            Projection::Orthographic => -q.depth,
        };
        Some([q.x * s, q.y * s, z])
    };
    match mark {
        Mark::Line { points, colour, width, dash } => {
            let colour = linear_rgb(*colour);
            let projected: Vec<Option<[f64; 3]>> = points.iter().map(|&p| project(p)).collect();
            let hw = 0.5 * width * s;
            let mut dasher = dash.map(|[on, off]| Dasher::new(on * s, off * s));
            for pair in projected.windows(2) {
                if let [Some(a), Some(b)] = *pair {
                    match &mut dasher {
                        None => quad(a, b, hw, colour, out),
                        Some(d) => d.segment(a, b, &mut |a, b| quad(a, b, hw, colour, out)),
                    }
                }
            }
        }
        Mark::Dot { at, radius, fill, outline } => {
            if let Some(c) = project(*at) {
                if let Some(o) = outline {
                    disc(c, (radius + 1.0) * s, linear_rgb(*o), out);
                }
                disc(c, radius * s, linear_rgb(*fill), out);
            }
        }
        Mark::Arrow { from, to, colour, width } => {
            if let (Some(a), Some(b)) = (project(*from), project(*to)) {
                let colour = linear_rgb(*colour);
                let hw = 0.5 * width * s;
                quad(a, b, hw, colour, out);
                for wing in arrow_head([a[0], a[1]], [b[0], b[1]], ARROW_HEAD_PX * s) {
                    quad(b, [wing[0], wing[1], b[2]], hw, colour, out);
                }
            }
        }
    }
}

/// Length of an arrow head's wings in pixels (at most a third of the arrow).
pub(crate) const ARROW_HEAD_PX: f64 = 7.0;

/// The two wing tips of an arrow head at `b` for the arrow `a → b`, wings of `len` (at most
/// a third of the arrow's length), 25° off the shaft; none for a zero-length arrow.
pub(crate) fn arrow_head(a: [f64; 2], b: [f64; 2], len: f64) -> Vec<[f64; 2]> {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l = (dx * dx + dy * dy).sqrt();
    if !(l > 1e-9) {
        return Vec::new();
    }
    let len = len.min(l / 3.0);
    let (ux, uy) = (dx / l, dy / l);
    let (s, c) = 25f64.to_radians().sin_cos();
    [s, -s]
        .into_iter()
        .map(|s| {
            // Rotate the backwards direction by ±25°.
            let (bx, by) = (-ux, -uy);
            [b[0] + len * (c * bx - s * by), b[1] + len * (s * bx + c * by)]
        })
        .collect()
}

/// Splits segments into dashes, carrying the pattern's phase from one segment to the next.
pub(crate) struct Dasher {
    on: f64,
    off: f64,
    /// Position within the pattern `[0, on + off)`.
    phase: f64,
}

impl Dasher {
    pub(crate) fn new(on: f64, off: f64) -> Self {
        Self { on: on.max(1e-6), off: off.max(0.0), phase: 0.0 }
    }

    /// Calls `emit` with the dashes of `a → b` (interpolating every coordinate).
    pub(crate) fn segment(&mut self, a: [f64; 3], b: [f64; 3], emit: &mut impl FnMut([f64; 3], [f64; 3])) {
        let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        let at = |t: f64| [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t];
        if !(len > 0.0) {
            return;
        }
        let period = self.on + self.off;
        let mut s = 0.0;
        while s < len {
            let (drawing, left) =
                if self.phase < self.on { (true, self.on - self.phase) } else { (false, period - self.phase) };
            let step = left.min(len - s);
            if drawing {
                emit(at(s / len), at((s + step) / len));
            }
            s += step;
            self.phase += step;
            if self.phase >= period - 1e-12 {
                self.phase = 0.0;
            }
        }
    }
}

/// A line of half-width `hw` from `a` to `b` (sample units), with square caps.
fn quad(a: [f64; 3], b: [f64; 3], hw: f64, colour: Vec3A, out: &mut Vec<MarkTri>) {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l = (dx * dx + dy * dy).sqrt();
    let (ux, uy) = if l > 1e-9 { (dx / l, dy / l) } else { (1.0, 0.0) };
    let (nx, ny) = (-uy * hw, ux * hw);
    let (ex, ey) = (ux * hw, uy * hw);
    let p = |q: [f64; 3], sx: f64, sy: f64| [(q[0] + sx) as f32, (q[1] + sy) as f32, q[2] as f32];
    let c = [p(a, nx - ex, ny - ey), p(b, nx + ex, ny + ey), p(b, -nx + ex, -ny + ey), p(a, -nx - ex, -ny - ey)];
    out.push(MarkTri { v: [c[0], c[1], c[2]], colour });
    out.push(MarkTri { v: [c[0], c[2], c[3]], colour });
}

/// A disc of radius `r` (sample units) at `c`, facing the eye.
fn disc(c: [f64; 3], r: f64, colour: Vec3A, out: &mut Vec<MarkTri>) {
    const SIDES: usize = 16;
    let at = |k: usize| {
        let (s, co) = (std::f64::consts::TAU * k as f64 / SIDES as f64).sin_cos();
        [(c[0] + r * co) as f32, (c[1] + r * s) as f32, c[2] as f32]
    };
    let centre = [c[0] as f32, c[1] as f32, c[2] as f32];
    for k in 0..SIDES {
        out.push(MarkTri { v: [centre, at(k), at(k + 1)], colour });
    }
}

/// sRGB (0..=1) to linear.
fn srgb_to_linear(c: f32) -> f32 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// An 8-bit sRGB colour in linear RGB.
fn linear_rgb(c: Rgb) -> Vec3A {
    Vec3A::new(
        srgb_to_linear(f32::from(c[0]) / 255.0),
        srgb_to_linear(f32::from(c[1]) / 255.0),
        srgb_to_linear(f32::from(c[2]) / 255.0),
    )
}

/// Linear to 8-bit sRGB by table.
struct SrgbLut([u8; Self::N + 1]);

impl SrgbLut {
    const N: usize = 4096;

    fn new() -> Self {
        let mut t = [0u8; Self::N + 1];
        for (i, v) in t.iter_mut().enumerate() {
            let x = i as f64 / Self::N as f64;
            let s = if x <= 0.003_130_8 { 12.92 * x } else { 1.055 * x.powf(1.0 / 2.4) - 0.055 };
            *v = (s * 255.0).round().clamp(0.0, 255.0) as u8;
        }
        Self(t)
    }

    fn encode(&self, c: f32) -> u8 {
        // Truncation after adding a half rounds (the value is non-negative); NaN gives 0.
        let i = (c.clamp(0.0, 1.0) * Self::N as f32 + 0.5) as usize;
        self.0[i.min(Self::N)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> TriMesh {
        TriMesh {
            positions: vec![
                DVec3::new(-1.0, -1.0, 0.0),
                DVec3::new(1.0, -1.0, 0.0),
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::new(-1.0, 1.0, 0.0),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            ..TriMesh::default()
        }
    }

    #[test]
    fn shared_edges_have_no_cracks() {
        // Front view of a square of two triangles, no margin: every pixel is covered once.
        let opts = RenderOptions::DEFAULT
            .with_view(View::Front)
            .with_projection(Projection::Orthographic)
            .with_size(ImageSize::new(64, 64).unwrap())
            .with_supersample(1);
        let opts = RenderOptions { margin: 0.0, ..opts };
        let image = render_mesh(&square(), &opts);
        let bg = [BACKGROUND[0], BACKGROUND[1], BACKGROUND[2], 255];
        assert!(image.iter_pixels().all(|p| p != bg), "a pixel shows the background");
        // Front facing (counter-clockwise from +z): not the back colour.
        let centre = image.pixel(32, 32).unwrap();
        assert!(centre[2] > centre[0], "{centre:?}");
    }

    #[test]
    fn back_faces_take_the_back_colour() {
        let mut mesh = square();
        for t in &mut mesh.triangles {
            t.swap(1, 2);
        }
        let opts = RenderOptions::DEFAULT.with_view(View::Front).with_size(ImageSize::new(32, 32).unwrap());
        let image = render_mesh(&mesh, &opts);
        let centre = image.pixel(16, 16).unwrap();
        assert!(centre[0] > centre[2], "{centre:?}");
    }

    #[test]
    fn skipping_hidden_triangles_changes_no_sample() {
        // Random triangles (many small, some slivers and large ones, depths crossing) drawn
        // in two passes as `render` does: the second pass with the tile test must leave
        // exactly the samples it leaves without it.
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut rnd = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let (width, rows) = (100, 40);
        let mut triangle = || -> [[f32; 3]; 3] {
            let (cx, cy, z) = (rnd() * 110.0 - 5.0, rnd() * 50.0 - 5.0, 1.0 + rnd());
            let size = [1.5, 4.0, 12.0, 60.0][(rnd() * 4.0) as usize];
            let tilt = [0.0, 0.01, 0.5, 50.0][(rnd() * 4.0) as usize];
            std::array::from_fn(|_| {
                let (dx, dy) = ((rnd() - 0.5) * size, (rnd() - 0.5) * size);
                [(cx + dx) as f32, (cy + dy) as f32, (z + tilt * dx / size) as f32]
            })
        };
        let mut skipped = 0;
        for round in 0..40 {
            let tris: Vec<[[f32; 3]; 3]> = (0..300).map(|_| triangle()).collect();
            let mut draw = |cull: bool| {
                let (mut depth, mut ids) = (vec![f32::NEG_INFINITY; width * rows], vec![NONE; width * rows]);
                let mut band = Band { depth: &mut depth, ids: &mut ids, width, y0: 0, y1: rows };
                for (k, &v) in tris[..150].iter().enumerate() {
                    band.triangle(v, k as u32, false, None);
                }
                let mut tiles = Vec::new();
                band.farthest_per_tile(&mut tiles);
                for (k, &v) in tris[150..].iter().enumerate() {
                    skipped += usize::from(band.triangle(v, 150 + k as u32, false, cull.then_some(&tiles[..])));
                }
                (depth, ids)
            };
            let (plain, culled) = (draw(false), draw(true));
            assert_eq!(plain.1, culled.1, "ids, round {round}");
            assert!(plain.0.iter().zip(&culled.0).all(|(a, b)| a.to_bits() == b.to_bits()), "depths, round {round}");
        }
        // The test skipped some (it is not vacuous).
        assert!(skipped > 100, "{skipped} skipped");
    }

    #[test]
    fn dashes_alternate() {
        let mut d = Dasher::new(2.0, 1.0);
        let mut dashes = Vec::new();
        d.segment([0.0, 0.0, 0.0], [4.0, 0.0, 0.0], &mut |a, b| dashes.push((a[0], b[0])));
        d.segment([4.0, 0.0, 0.0], [7.0, 0.0, 0.0], &mut |a, b| dashes.push((a[0], b[0])));
        assert_eq!(dashes, [(0.0, 2.0), (3.0, 4.0), (4.0, 5.0), (6.0, 7.0)]);
    }

    #[test]
    fn lut_ends() {
        let lut = SrgbLut::new();
        assert_eq!((lut.encode(0.0), lut.encode(1.0), lut.encode(2.0), lut.encode(f32::NAN)), (0, 255, 255, 0));
        assert_eq!(lut.encode(linear_rgb([168, 186, 214]).x), 168);
    }
}
