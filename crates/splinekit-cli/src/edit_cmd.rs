//! `splinekit edit [FILE]`: opens the editor window.

use std::path::PathBuf;

use clap::Args;

/// Open the interactive editor: 2D curve editing and the swept surfaces or a mesh in 3D.
///
/// FILE may be an SWP file (edited as the document), or an OBJ, glb, PLY or STL mesh (shown with
/// Loop subdivision; an OBJ with a spline header is rebuilt from its spline). Files can also
/// be opened from the path field at the top of the window. Press h in the window for the
/// keyboard shortcuts. Needs a display (X11 or Wayland) and a Vulkan, Metal, DX12 or GL driver.
#[derive(Debug, Args)]
#[command(after_help = "Examples:\n  splinekit edit\n  splinekit edit wineglass.swp\n  splinekit edit bunny.obj")]
pub struct EditArgs {
    /// The file to open.
    pub file: Option<PathBuf>,
}

/// Runs the editor until its window is closed.
#[cfg(feature = "editor")]
pub fn run(args: &EditArgs) -> anyhow::Result<()> {
    splinekit_editor::run(args.file.clone())
}

/// This binary was built without the editor.
#[cfg(not(feature = "editor"))]
pub fn run(_args: &EditArgs) -> anyhow::Result<()> {
    anyhow::bail!(
        "this splinekit was built without the editor (cargo feature `editor`); \
         build it with `cargo build --release -p splinekit-cli` to get `splinekit edit`"
    )
}
