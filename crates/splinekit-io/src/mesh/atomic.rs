//! Atomic file writes: all or nothing.
//!
//! [`write_file`] writes through a temporary file in the target's directory and renames it
//! over the target only after everything was written and synced. If anything fails — the
//! directory does not exist, the callback returns an error or panics, the disk is full, the
//! rename is refused — the temporary file is removed and the target is left as it was: there
//! is never a partial output file.
//!
//! ```
//! use std::io::Write;
//!
//! # let dir = std::env::temp_dir().join(format!("splinekit-atomic-doc-{}", std::process::id()));
//! # std::fs::create_dir_all(&dir)?;
//! let path = dir.join("hello.txt");
//! splinekit_io::atomic::write_file(&path, |w| w.write_all(b"hello\n"))?;
//! assert_eq!(std::fs::read_to_string(&path)?, "hello\n");
//!
//! // A failing callback leaves the old contents in place.
//! let failed: std::io::Result<()> = splinekit_io::atomic::write_file(&path, |w| {
//!     w.write_all(b"half a file")?;
//!     Err(std::io::Error::other("the mesh generator gave up"))
//! });
//! assert!(failed.is_err());
//! assert_eq!(std::fs::read_to_string(&path)?, "hello\n");
//! # std::fs::remove_dir_all(&dir)?;
//! # Ok::<(), std::io::Error>(())
//! ```

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// How many temporary names are tried before giving up when they already exist.
const MAX_TEMP_ATTEMPTS: u32 = 64;

/// Counter that makes temporary names unique within the process.
static TEMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// An I/O error of [`write_file`], naming the target path and what was being done.
///
/// Displays as `PATH: cannot ACTION: OS MESSAGE`, for example
/// `out/vase.obj: cannot create temporary file: No such file or directory (os error 2)`.
#[derive(Debug, thiserror::Error)]
#[error("{}: cannot {action}: {error}", path.display())]
pub struct WriteFileError {
    path: PathBuf,
    action: &'static str,
    error: io::Error,
}

impl WriteFileError {
    fn new(path: &Path, action: &'static str, error: io::Error) -> Self {
        Self { path: path.to_owned(), action, error }
    }

    /// The file that was to be written (the target, not the temporary file).
    #[must_use]
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// What was being done: `create temporary file`, `write`, `sync` or `rename temporary
    /// file` (or `write to a path without a file name`).
    #[must_use]
    pub fn action(&self) -> &'static str {
        self.action
    }

    /// The operating system's error.
    #[must_use]
    pub fn io_error(&self) -> &io::Error {
        &self.error
    }

    /// The action and the operating system's error.
    #[must_use]
    pub fn into_parts(self) -> (&'static str, io::Error) {
        (self.action, self.error)
    }
}

impl From<WriteFileError> for io::Error {
    /// Keeps the [`io::ErrorKind`] and puts the path and action into the message.
    fn from(e: WriteFileError) -> Self {
        io::Error::new(e.error.kind(), e.to_string())
    }
}

/// Removes the temporary file when dropped, unless disarmed after the rename.
#[derive(Debug)]
struct TempGuard {
    path: PathBuf,
    armed: bool,
}

impl Drop for TempGuard {
    fn drop(&mut self) {
        // renamed or removed: no longer a temporary file to clean up on interruption
        live().retain(|p| *p != self.path);
        if self.armed {
            // Best effort: there is nothing better to do with an error while cleaning up.
            let _ = fs::remove_file(&self.path);
        }
    }
}

/// Writes the file at `path` atomically: `write` fills a buffered temporary file in the same
/// directory, which then replaces `path` by a rename.
///
/// - On success the file holds exactly what `write` wrote (it was flushed and synced to disk
///   before the rename). An existing file is replaced; its permissions are copied to the new
///   file (best effort). A symbolic link at `path` is replaced by a regular file, not followed.
/// - On failure — of the callback (an error or a panic) or of any I/O step — the temporary
///   file is removed and `path` is untouched: a new file is not created, an existing one keeps
///   its old contents.
///
/// - A device or pipe at `path` (`/dev/null`, a FIFO) is written in place: no temporary file,
///   no rename (which would put a regular file in its place).
/// - A read-only file at `path` is refused (`cannot replace: the file is read-only`) unless
///   [`set_replace_read_only`] allows it (a command's `--force`).
///
/// The temporary file is named `.NAME.PID-N.tmp` after the target's file name `NAME`; it is
/// hidden on Unix and never left behind except when the process is killed while writing.
///
/// The callback's error type `E` only has to be convertible from [`WriteFileError`], which
/// [`io::Error`], [`MeshIoError`](super::MeshIoError) and `anyhow::Error` all are; the
/// callback's value is returned.
///
/// # Errors
///
/// The callback's error, or a [`WriteFileError`] (converted into `E`) naming `path` when the
/// temporary file cannot be created (for example, the directory does not exist), written,
/// synced or renamed, or when `path` has no file name.
pub fn write_file<T, E, F>(path: impl AsRef<Path>, write: F) -> Result<T, E>
where
    F: FnOnce(&mut BufWriter<File>) -> Result<T, E>,
    E: From<WriteFileError>,
{
    let (staged, value) = stage_file(path, write)?;
    staged.commit()?;
    Ok(value)
}

/// A file written to its temporary name by [`stage_file`], waiting to replace its target:
/// [`commit`](Self::commit) renames it into place; dropping it removes it.
///
/// Staging every file of a set before committing any writes all of them or none: an error
/// while writing the third file of three leaves no file of the set.
#[derive(Debug)]
#[must_use = "a staged file is removed unless committed"]
pub struct Staged {
    /// The temporary file, or `None` when the target was written in place (a device or pipe).
    guard: Option<TempGuard>,
    target: PathBuf,
    dir: PathBuf,
}

/// The way out that the refusal to replace a read-only file names: the command line's flag (a
/// program without it, such as the editor, puts its own in its place).
pub const READ_ONLY_HINT: &str = "--force replaces it";

/// Whether [`write_file`] may replace a read-only file (off unless a program's `--force` turns
/// it on for the whole process).
static REPLACE_READ_ONLY: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Lets [`write_file`] and [`stage_file`] replace read-only files (for a command's `--force`),
/// or stops them again; process-wide.
pub fn set_replace_read_only(allow: bool) {
    REPLACE_READ_ONLY.store(allow, Ordering::Relaxed);
}

impl Staged {
    /// The file the staged one will replace.
    #[must_use]
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Renames the staged file over its target.
    ///
    /// # Errors
    /// A [`WriteFileError`] naming the target when the rename is refused (the staged file is
    /// then removed).
    pub fn commit(mut self) -> Result<(), WriteFileError> {
        let Some(guard) = &mut self.guard else { return Ok(()) };
        fs::rename(&guard.path, &self.target)
            .map_err(|e| WriteFileError::new(&self.target, "rename temporary file", e))?;
        guard.armed = false;
        sync_dir(&self.dir);
        Ok(())
    }
}

/// The first half of [`write_file`]: `write` fills a temporary file next to `path`, which is
/// flushed and synced but not yet renamed; see [`Staged`]. A directory at `path` is refused
/// at once (a rename could not replace it).
///
/// # Errors
/// As [`write_file`], before the rename.
pub fn stage_file<T, E, F>(path: impl AsRef<Path>, write: F) -> Result<(Staged, T), E>
where
    F: FnOnce(&mut BufWriter<File>) -> Result<T, E>,
    E: From<WriteFileError>,
{
    let path = path.as_ref();
    let fail = |action, error| E::from(WriteFileError::new(path, action, error));
    let Some(name) = path.file_name() else {
        let error = io::Error::new(io::ErrorKind::InvalidInput, "the path does not end in a file name");
        return Err(fail("write to a path without a file name", error));
    };
    if path.is_dir() {
        let error = io::Error::new(io::ErrorKind::IsADirectory, "a directory of that name is in the way");
        return Err(fail("write", error));
    }
    let dir = match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    };
    if let Ok(meta) = fs::symlink_metadata(path) {
        let kind = meta.file_type();
        if !kind.is_file() && !kind.is_symlink() {
            // a device or a pipe (`/dev/null`, `/dev/stdout`, a FIFO): written in place, since
            // a rename would put a regular file where it was
            let file = OpenOptions::new().write(true).open(path).map_err(|e| fail("open", e))?;
            let mut writer = BufWriter::with_capacity(1 << 16, file);
            let value = write(&mut writer)?;
            writer.into_inner().map_err(|e| fail("write", e.into_error()))?;
            return Ok((Staged { guard: None, target: path.to_path_buf(), dir: dir.to_path_buf() }, value));
        }
        if kind.is_file() && meta.permissions().readonly() && !REPLACE_READ_ONLY.load(Ordering::Relaxed) {
            let error =
                io::Error::new(io::ErrorKind::PermissionDenied, format!("the file is read-only ({READ_ONLY_HINT})"));
            return Err(fail("replace", error));
        }
    }

    let (file, guard) = create_temp(dir, &name.to_string_lossy()).map_err(|e| fail("create temporary file", e))?;
    if let Ok(meta) = fs::metadata(path) {
        // Best effort: keep the permissions of the file being replaced.
        let _ = file.set_permissions(meta.permissions());
    }
    let mut writer = BufWriter::with_capacity(1 << 16, file);
    let value = write(&mut writer)?;
    let file = writer.into_inner().map_err(|e| fail("write", e.into_error()))?;
    file.sync_all().map_err(|e| fail("sync", e))?;
    drop(file);
    let staged = Staged { guard: Some(guard), target: path.to_path_buf(), dir: dir.to_path_buf() };
    Ok((staged, value))
}

/// The temporary files being written now (by every thread), so that an interrupted program
/// can remove them ([`remove_temporaries`]).
static LIVE: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

fn live() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Removes every temporary file that a write in progress (or a [`Staged`] file not yet
/// committed) holds, for a program that is being interrupted (Ctrl-C, SIGTERM): its handler
/// calls this before it exits, so no hidden `.NAME.PID-N.tmp` of a large output is left.
/// Returns how many were removed.
pub fn remove_temporaries() -> usize {
    let paths = std::mem::take(&mut *live());
    paths.iter().filter(|p| fs::remove_file(p).is_ok()).count()
}

/// Creates a new, uniquely named temporary file in `dir`.
fn create_temp(dir: &Path, name: &str) -> io::Result<(File, TempGuard)> {
    let pid = std::process::id();
    let mut last_error = None;
    for _ in 0..MAX_TEMP_ATTEMPTS {
        let n = TEMP_COUNTER.fetch_add(1, Ordering::Relaxed);
        let temp = dir.join(format!(".{name}.{pid}-{n}.tmp"));
        match OpenOptions::new().write(true).create_new(true).open(&temp) {
            Ok(file) => {
                live().push(temp.clone());
                return Ok((file, TempGuard { path: temp, armed: true }));
            }
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => last_error = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last_error.unwrap_or_else(|| io::Error::other("no free temporary file name")))
}

/// Makes the rename durable (Unix; best effort, errors are ignored).
fn sync_dir(dir: &Path) {
    #[cfg(unix)]
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
    #[cfg(not(unix))]
    let _ = dir;
}

#[cfg(test)]
mod tests {
    use std::io::Write;

    use super::*;

    fn scratch(tag: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("splinekit-atomic-{tag}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> =
            fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
        names.sort();
        names
    }

    #[test]
    fn replaces_and_leaves_no_temporary_file() {
        let dir = scratch("replace");
        let path = dir.join("a.txt");
        write_file(&path, |w| w.write_all(b"one")).unwrap();
        let n: io::Result<usize> = write_file(&path, |w| w.write_all(b"two").map(|()| 7));
        assert_eq!(n.unwrap(), 7);
        assert_eq!(fs::read(&path).unwrap(), b"two");
        assert_eq!(entries(&dir), ["a.txt"]);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn panicking_callback_leaves_nothing() {
        let dir = scratch("panic");
        let path = dir.join("p.txt");
        let result = std::panic::catch_unwind(|| {
            let _: io::Result<()> = write_file(&path, |w| {
                w.write_all(b"partial").unwrap();
                panic!("boom");
            });
        });
        assert!(result.is_err());
        assert!(entries(&dir).is_empty(), "{:?}", entries(&dir));
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn path_without_file_name_is_an_error() {
        let e: io::Error = write_file("..", |w| w.write_all(b"x")).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::InvalidInput);
        assert!(e.to_string().starts_with("..: cannot write to a path without a file name"), "{e}");
    }
}
