//! A fuzz harness for splinekit that any developer can run for a bounded time on stable
//! Rust (issue #38).
//!
//! Each case is one input file, made from the case's seed and index alone (so any case can
//! be replayed by itself):
//!
//! - **generated**, structure-aware: SWP documents with every curve and surface keyword and
//!   option ([`gen_swp`]), and OBJ, PLY (ASCII and binary), STL (ASCII and binary) and glb
//!   meshes ([`gen_mesh`]), valid in grammar with extreme values and odd topology;
//! - **mutated**: the repository's example and fixture files (and files the project's
//!   writers make from them) with bytes flipped, inserted, deleted, duplicated and spliced
//!   ([`mutate`], [`corpus`]);
//! - or a generated file mutated.
//!
//! Every input is fed, in-process, to the reader and then to the library paths of every
//! command ([`feed`]). The oracle:
//!
//! - **no panic** (each case runs under `catch_unwind`, and the panic hook keeps the
//!   message and location);
//! - **no infinity or NaN in a successful result** ([`check`]), unless the input itself has
//!   a number beyond [`check::LARGE`] (then results may overflow, and the commands refuse
//!   them: counted as refusals);
//! - **written files read back** (SWP documents, annotated OBJ headers and every mesh
//!   format, with the same counts);
//! - **time and memory within a bound proportional to the input**: by default
//!   `2 s + 50 µs·bytes` and `256 MiB + 2000·bytes` of peak live heap (measured by the
//!   counting allocator [`alloc::Counting`], which the binary and the CI test install).
//!   Every path is bounded by the library's own limits or by the harness's small ones
//!   ([`feed::MAX_POINTS`], [`feed::MAX_TRIANGLES`], [`feed::MAX_SUBDIVIDED`]), so a case
//!   that is slower or bigger than that is something the library does per input byte far
//!   more than it should. In a debug build the time bound is 10 times longer.
//!
//! An input the readers refuse with an error is fine; text-reader errors without a line and
//! column are counted (not failed).
//!
//! Run it with `cargo run --release -p splinekit-fuzz -- --seconds 600` (see `--help`).

pub mod alloc;
pub mod check;
pub mod corpus;
pub mod feed;
pub mod gen_mesh;
pub mod gen_swp;
pub mod harness;
pub mod mutate;
pub mod rng;
pub mod values;

use std::path::Path;

use splinekit_io::mesh::MeshFormat;

pub use harness::{Config, Summary, run};

/// The input formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Format {
    /// SWP curve and surface descriptions.
    Swp,
    /// Wavefront OBJ.
    Obj,
    /// PLY, ASCII or binary.
    Ply,
    /// STL, ASCII or binary.
    Stl,
    /// Binary glTF.
    Glb,
}

impl Format {
    /// Every format, in the order cases cycle through them.
    pub const ALL: [Self; 5] = [Self::Swp, Self::Obj, Self::Ply, Self::Stl, Self::Glb];

    /// The extension, lowercase: `swp`, `obj`, `ply`, `stl`, `glb`.
    #[must_use]
    pub fn extension(self) -> &'static str {
        match self {
            Self::Swp => "swp",
            Self::Obj => "obj",
            Self::Ply => "ply",
            Self::Stl => "stl",
            Self::Glb => "glb",
        }
    }

    /// The format of this extension (any case), if any.
    #[must_use]
    pub fn from_extension(extension: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.extension().eq_ignore_ascii_case(extension))
    }

    /// The format of a path's extension, if any.
    #[must_use]
    pub fn from_path(path: &Path) -> Option<Self> {
        path.extension().and_then(|e| e.to_str()).and_then(Self::from_extension)
    }

    /// The position in [`ALL`](Self::ALL).
    #[must_use]
    pub fn index(self) -> usize {
        self as usize
    }

    /// Whether files of this format are always binary.
    #[must_use]
    pub fn is_binary(self) -> bool {
        self == Self::Glb
    }

    /// The mesh format, for every format but SWP.
    #[must_use]
    pub fn mesh_format(self) -> Option<MeshFormat> {
        match self {
            Self::Swp => None,
            Self::Obj => Some(MeshFormat::Obj),
            Self::Ply => Some(MeshFormat::Ply),
            Self::Stl => Some(MeshFormat::Stl),
            Self::Glb => Some(MeshFormat::Glb),
        }
    }
}

impl std::fmt::Display for Format {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.extension())
    }
}

/// What kind of oracle failure a case showed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum FindingKind {
    /// A panic.
    Panic,
    /// An infinity or NaN in a successful result.
    NonFinite,
    /// A successful result that breaks an invariant (an index out of range, a parameter
    /// outside the domain, more points than promised).
    Invalid,
    /// Something written that does not read back the same.
    RoundTrip,
    /// Slower than the time bound.
    Slow,
    /// More peak memory than the memory bound.
    Memory,
}

impl std::fmt::Display for FindingKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Panic => "panic",
            Self::NonFinite => "non-finite result",
            Self::Invalid => "invalid result",
            Self::RoundTrip => "round trip",
            Self::Slow => "too slow",
            Self::Memory => "too much memory",
        })
    }
}

/// An oracle failure: its kind and what exactly went wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Finding {
    /// The kind.
    pub kind: FindingKind,
    /// What went wrong, where.
    pub detail: String,
}

impl Finding {
    /// A finding of `kind`.
    pub fn new(kind: FindingKind, detail: impl Into<String>) -> Self {
        Self { kind, detail: detail.into() }
    }
}

/// How a case went when the oracle found nothing wrong.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Outcome {
    /// The reader accepted the input.
    pub accepted: bool,
    /// The reader refused it with an error that has a position (or a name, for binary data).
    pub located: bool,
    /// Some result overflowed on an input with numbers beyond [`check::LARGE`].
    pub overflow: bool,
    /// The reader's error message, if it refused the input.
    pub message: Option<String>,
}

impl Outcome {
    /// Accepted by the reader.
    #[must_use]
    pub fn accepted() -> Self {
        Self { accepted: true, located: true, ..Self::default() }
    }

    /// Refused by the reader, with an error that is `located` or not.
    #[must_use]
    pub fn refused(located: bool) -> Self {
        Self { located, ..Self::default() }
    }

    /// With the reader's error message.
    #[must_use]
    pub fn with_message(mut self, message: String) -> Self {
        self.message = Some(message);
        self
    }
}
