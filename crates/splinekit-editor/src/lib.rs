//! The splinekit editor (`splinekit edit [FILE]`): 2D curve editing and the surfaces swept
//! from the curves, or a mesh opened for viewing with its subdivision.
//!
//! The window has a file bar (`Open…`, `Save`, `Save as…`, `Export mesh…`, undo, redo, the
//! preset scene, help), a left panel (curves, kind, closed, plane, what to show), the 2D curve
//! view in the middle, a right panel with the surface or mesh, its subdivision and the 3D view
//! ([`View3d`]), and a status line for messages and errors. An error never changes the
//! document.
//!
//! **Files.** The document knows its file and its kind ([`DocKind`]): Save (Ctrl+S) writes an
//! SWP document back to its file, and asks for a name (as Save as, Ctrl+Shift+S) for a new
//! document or a mesh opened for viewing, which is never written back. Open (Ctrl+O), Save as
//! and Export mesh use a file dialog in the window ([`files::FileDialog`]). A document is
//! checked before it is written, with the rules the reader applies: a file the editor cannot
//! read back is never written. The window title is `NAME — splinekit`, with a leading `*`
//! while the document has unsaved changes; closing the window, opening a file (also by
//! dropping it on the window), New (Ctrl+N), the preset scene and Close mesh ask first
//! (`Save` / `Discard` / `Cancel`). Opening a file is one undo step.
//!
//! The 3D view shows the document's surfaces, swept again whenever the document changes (so
//! they follow a dragged point live), or the mesh at the subdivision level shown. The
//! control points of an active 3D curve are handles there too, dragged in the plane parallel
//! to the screen.
//!
//! Keyboard (when no text field has focus; every press counts, however slow the frame): `r`
//! preset scene, `s` cycle the spline kind, `c` clear the curve, `a` arc-length markers, `l`
//! control polygon, `w` wireframe, `n` normals (curve and surface), `f` fit both views, `h` or
//! `?` help, Delete the selected point, Ctrl+Z undo, Ctrl+Shift+Z (or Ctrl+Y) redo, Ctrl+S save,
//! Ctrl+Shift+S save as, Ctrl+O open, Ctrl+N new.

pub mod compare;
pub mod doc;
pub mod files;
pub mod view2d;
pub mod view3d;
pub mod work;

mod app;
mod curve_panel;
mod dialog;
mod open;
mod point_panel;
mod save;
mod scene;
mod shortcuts;
mod subdivision;
mod surface_panel;
mod surfaces;
mod top_bar;
mod unsaved;
mod windows;

pub use app::{EditorApp, run};
pub use doc::{DocKind, Document, ViewedMesh};
pub use open::BACKGROUND_BYTES;
pub use scene::COLOUR_MAX_TRIANGLES;
pub use shortcuts::SHORTCUTS;
pub use subdivision::{BACKGROUND_FACES, MeshState};
pub use surface_panel::{DEFAULT_SLICES, RevolveAxis};
pub use surfaces::{EDITOR_MAX_TRIANGLES, LIVE_TRIANGLES, PREVIEW_TRIANGLES, SweptSurfaces};
pub use top_bar::Layout;
pub use unsaved::Pending;
pub use view2d::{Plane, View2d};
pub use view3d::{View3d, View3dSettings};
pub use windows::MOUSE;
