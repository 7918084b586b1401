//! Smoke tests of the real editor window: `splinekit edit wineglass.swp` under a virtual X
//! server (Xvfb), screenshots with `xwd`, converted with netpbm.
//!
//! - The window shows both views (the 2D view's light background and the 3D view's lit
//!   surface); the screenshot is saved as `editor-window.png` in Cargo's temporary directory
//!   for integration tests.
//! - Closing the window as a window manager does (a `WM_DELETE_WINDOW` client message) with
//!   unsaved changes (the key `s`, on a copy of the file) asks first: the window stays, the
//!   title keeps its `*`, the file is untouched and the question is drawn (saved as
//!   `editor-close-question.png` beside the other); Escape cancels it; closing again and
//!   clicking Discard ends the editor.
//!
//! Needs the apt packages `xvfb x11-apps netpbm`, and for the second test `xdotool
//! python3-xlib` (scripts/install-test-deps.sh installs them); where they are missing, a test
//! prints why and passes without running.

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// How long the window may take to show both views (a cold software renderer is slow).
const TIMEOUT: Duration = Duration::from_secs(120);

/// How long the open window may take to answer a key press, click or close request.
const ANSWER: Duration = Duration::from_secs(20);

/// How long one helper program (xdotool, python3) may run.
const TOOL: Duration = Duration::from_secs(10);

/// Kills the child process when dropped.
struct Killed(Child);

impl Drop for Killed {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn on_path(program: &str) -> Option<PathBuf> {
    std::env::var_os("PATH")?.to_str()?.split(':').map(|d| Path::new(d).join(program)).find(|p| p.is_file())
}

/// An RGB image from a binary PPM (P6, maxval 255).
struct Image {
    width: usize,
    height: usize,
    rgb: Vec<u8>,
}

impl Image {
    fn parse_ppm(bytes: &[u8]) -> Result<Self, String> {
        // header: P6 <ws> width <ws> height <ws> maxval <one ws> data (no comments from xwdtopnm)
        let mut fields = Vec::new();
        let mut i = 0;
        while fields.len() < 4 {
            while i < bytes.len() && bytes[i].is_ascii_whitespace() {
                i += 1;
            }
            let start = i;
            while i < bytes.len() && !bytes[i].is_ascii_whitespace() {
                i += 1;
            }
            if start == i {
                return Err("truncated PPM header".into());
            }
            fields.push(String::from_utf8_lossy(&bytes[start..i]).into_owned());
        }
        if fields[0] != "P6" || fields[3] != "255" {
            return Err(format!("not an 8-bit P6 PPM: {fields:?}"));
        }
        let width: usize = fields[1].parse().map_err(|e| format!("width: {e}"))?;
        let height: usize = fields[2].parse().map_err(|e| format!("height: {e}"))?;
        let rgb = bytes.get(i + 1..i + 1 + 3 * width * height).ok_or("truncated PPM data")?.to_vec();
        Ok(Self { width, height, rgb })
    }

    fn count(&self, x0: usize, x1: usize, f: impl Fn([u8; 3]) -> bool) -> usize {
        (0..self.height)
            .flat_map(|y| (x0..x1.min(self.width)).map(move |x| (x, y)))
            .filter(|&(x, y)| {
                let k = 3 * (y * self.width + x);
                f([self.rgb[k], self.rgb[k + 1], self.rgb[k + 2]])
            })
            .count()
    }
}

/// A screenshot of the root window of `display` as PPM bytes.
fn screenshot(display: &str) -> Result<Vec<u8>, String> {
    let xwd = Command::new("xwd")
        .args(["-root", "-silent", "-display", display])
        .output()
        .map_err(|e| format!("xwd: {e}"))?;
    if !xwd.status.success() {
        return Err(format!("xwd failed: {}", String::from_utf8_lossy(&xwd.stderr)));
    }
    let mut conv = Command::new("xwdtopnm")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .map_err(|e| format!("xwdtopnm: {e}"))?;
    let mut stdin = conv.stdin.take().expect("piped");
    let writer = std::thread::spawn(move || std::io::Write::write_all(&mut stdin, &xwd.stdout));
    let mut out = Vec::new();
    conv.stdout.take().expect("piped").read_to_end(&mut out).map_err(|e| e.to_string())?;
    let _ = writer.join();
    conv.wait().map_err(|e| e.to_string())?;
    Ok(out)
}

/// A virtual X server on a free display, and that display's name (`:N`).
/// The tests run one at a time: two Xvfb servers started at once with `-displayfd` can pick
/// the same free display number, and one of the editors then finds no server.
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn start_xvfb() -> (Killed, String) {
    // Xvfb picks a free display and writes its number to the descriptor given (stdout)
    let mut xvfb = Command::new("Xvfb")
        .args(["-displayfd", "1", "-screen", "0", "1280x800x24", "-nolisten", "tcp"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("start Xvfb");
    let stdout = xvfb.stdout.take().expect("piped");
    let xvfb = Killed(xvfb);
    let mut line = String::new();
    BufReader::new(stdout).read_line(&mut line).expect("Xvfb display number");
    let display = format!(":{}", line.trim());
    assert!(line.trim().parse::<u32>().is_ok(), "Xvfb wrote {line:?} instead of a display number");
    (xvfb, display)
}

/// The editor on `file` in `display`, with its stderr in a log file; the runtime directory
/// and the log are named after `tag` (each test its own).
struct Editor {
    child: Killed,
    runtime: PathBuf,
    log: PathBuf,
}

impl Editor {
    fn start(display: &str, file: &Path, tag: &str) -> Self {
        let id = std::process::id();
        let runtime = std::env::temp_dir().join(format!("splinekit-xdg-{tag}-{id}"));
        std::fs::create_dir_all(&runtime).unwrap();
        let log = std::env::temp_dir().join(format!("splinekit-edit-{tag}-{id}.log"));
        let child = Killed(
            Command::new(env!("CARGO_BIN_EXE_splinekit"))
                .arg("edit")
                .arg(file)
                .env("DISPLAY", display)
                .env("XDG_RUNTIME_DIR", &runtime)
                .env_remove("WAYLAND_DISPLAY")
                .stdout(Stdio::null())
                .stderr(std::fs::File::create(&log).unwrap())
                .spawn()
                .expect("start splinekit edit"),
        );
        Self { child, runtime, log }
    }

    /// The editor's stderr so far.
    fn log(&self) -> String {
        std::fs::read_to_string(&self.log).unwrap_or_else(|e| format!("(no log: {e})"))
    }

    /// Fails the test with `message` and the editor's log.
    fn fail(&self, message: &str) -> ! {
        panic!("{message}\n--- the editor's stderr ({}):\n{}", self.log.display(), self.log())
    }

    /// Fails the test if the editor has exited.
    fn assert_running(&mut self, when: &str) {
        if let Some(status) = self.child.0.try_wait().unwrap() {
            self.fail(&format!("the editor exited ({status}) {when}"));
        }
    }

    /// Screenshots until the window shows both views, or [`TIMEOUT`]: the last screenshot
    /// (PPM), its light 2D-view pixels and its surface pixels.
    fn wait_for_both_views(&mut self, display: &str) -> (Vec<u8>, usize, usize) {
        let start = Instant::now();
        loop {
            self.assert_running("before showing its window");
            let bytes = screenshot(display).expect("screenshot");
            let image = Image::parse_ppm(&bytes).expect("xwdtopnm output");
            assert_eq!((image.width, image.height), (1280, 800));
            let (light, surface) = image.views();
            if (light > 100_000 && surface > 20_000) || start.elapsed() > TIMEOUT {
                return (bytes, light, surface);
            }
            std::thread::sleep(Duration::from_millis(500));
        }
    }

    /// Screenshots until `done` holds for one, or fails after [`ANSWER`] with `what`; the last
    /// screenshot is saved as `name` (see [`save_png`]). The editor must keep running meanwhile.
    fn wait_for_screen(&mut self, display: &str, what: &str, name: &str, done: impl Fn(&Image) -> bool) -> Image {
        let start = Instant::now();
        loop {
            self.assert_running(&format!("while waiting until {what}"));
            let bytes = screenshot(display).expect("screenshot");
            let image = Image::parse_ppm(&bytes).expect("xwdtopnm output");
            let ok = done(&image);
            if ok || start.elapsed() > ANSWER {
                let png = save_png(&bytes, name);
                if !ok {
                    self.fail(&format!("waited {ANSWER:?} in vain until {what} (last screenshot: {})", png.display()));
                }
                eprintln!("screenshot when {what}: {}", png.display());
                return image;
            }
            std::thread::sleep(Duration::from_millis(300));
        }
    }

    /// `program args` in `display` (see [`run`]): its stdout; fails the test if it fails.
    fn tool(&self, display: &str, program: &str, args: &[&str]) -> String {
        run(display, program, args).unwrap_or_else(|e| self.fail(&e))
    }

    /// The id of the editor's window (its title ends in "splinekit"), waiting up to [`ANSWER`].
    fn window(&mut self, display: &str) -> String {
        let start = Instant::now();
        loop {
            self.assert_running("while looking for its window");
            // xdotool search fails while nothing matches
            if let Ok(ids) = run(display, "xdotool", &["search", "--name", "splinekit$"])
                && let [id] = ids.split_whitespace().collect::<Vec<_>>()[..]
            {
                return id.to_owned();
            }
            if start.elapsed() > ANSWER {
                self.fail(&format!("no single window named …splinekit within {ANSWER:?}"));
            }
            std::thread::sleep(Duration::from_millis(200));
        }
    }

    /// The title of `window`.
    fn title(&self, display: &str, window: &str) -> String {
        self.tool(display, "xdotool", &["getwindowname", window]).trim_end_matches('\n').to_owned()
    }

    /// Waits up to [`ANSWER`] until the title of `window` passes `ok` (`expected` says how).
    fn wait_for_title(&mut self, display: &str, window: &str, ok: impl Fn(&str) -> bool, expected: &str) {
        let start = Instant::now();
        loop {
            self.assert_running("while waiting for its title to change");
            let title = self.title(display, window);
            if ok(&title) {
                return;
            }
            if start.elapsed() > ANSWER {
                self.fail(&format!("the window title is {title:?}, not {expected:?}, after {ANSWER:?}"));
            }
            std::thread::sleep(Duration::from_millis(200));
        }
    }
}

impl Drop for Editor {
    fn drop(&mut self) {
        let _ = self.child.0.kill();
        let _ = self.child.0.wait();
        let _ = std::fs::remove_dir_all(&self.runtime);
    }
}

impl Image {
    /// Light 2D-view pixels (its grey 250 background, on the left) and lit-surface pixels (the
    /// grey-blue glass, blue above red, brighter than the 3D view's dark background, on the
    /// right).
    fn views(&self) -> (usize, usize) {
        let light = self.count(0, 800, |[r, g, b]| r == 250 && g == 250 && b == 250);
        let surface = self.count(800, 1280, |[r, g, b]| {
            b > 110 && i32::from(b) - i32::from(r) >= 20 && g > r && b > g && i32::from(b) - i32::from(g) < 60
        });
        (light, surface)
    }

    fn pixel(&self, x: usize, y: usize) -> [u8; 3] {
        let k = 3 * (y * self.width + x);
        [self.rgb[k], self.rgb[k + 1], self.rgb[k + 2]]
    }

    /// The centre of the middle one of three buttons side by side (a question's row of
    /// buttons), if there is such a row: the first row of pixels, from the top, where three
    /// buttons (a fill of one colour, 20 to 200 pixels long, maybe framed by a pixel or two of
    /// other colours) stand on a background of one colour, 2 to 30 pixels between them, and no
    /// fourth button that close before or after them (a toolbar), the first starting in the left
    /// half of the screen (the question is centred). The button's height is where
    /// the fill's colour goes down its left end.
    fn middle_of_three_buttons(&self) -> Option<(usize, usize)> {
        /// A row of pixels as runs of one colour.
        struct Run {
            colour: [u8; 3],
            start: usize,
            len: usize,
        }
        /// A button at `runs[i..]` on `background`: the index after it, and its fill.
        fn button(runs: &[Run], mut i: usize, background: [u8; 3]) -> Option<(usize, &Run)> {
            let frame = |r: &Run| r.colour != background && r.len <= 2;
            if frame(runs.get(i)?) && runs.get(i + 1).is_some_and(|r| r.len > 2) {
                i += 1;
            }
            let fill = runs.get(i)?;
            if fill.colour == background || !(20..=200).contains(&fill.len) {
                return None;
            }
            i += 1;
            if runs.get(i).is_some_and(frame) {
                i += 1;
            }
            Some((i, fill))
        }
        for y in 0..self.height {
            let mut runs: Vec<Run> = Vec::new();
            for x in 0..self.width {
                let colour = self.pixel(x, y);
                match runs.last_mut() {
                    Some(run) if run.colour == colour => run.len += 1,
                    _ => runs.push(Run { colour, start: x, len: 1 }),
                }
            }
            for first in 0..runs.len() {
                let background = runs[first].colour;
                let gap = |i: usize, min: usize, max: usize| {
                    runs.get(i).is_some_and(|r| r.colour == background && (min..=max).contains(&r.len))
                };
                if !gap(first, 2, usize::MAX) {
                    continue;
                }
                // no button just before (on the same background): a toolbar
                let fill = |r: &Run| r.colour != background && (20..=200).contains(&r.len);
                let frame = |r: &Run| r.colour != background && r.len <= 2;
                let at = |i: usize, j: usize| i.checked_sub(j).map(|k| &runs[k]);
                let mut j = 1;
                if at(first, j).is_some_and(frame) && at(first, j + 1).is_some_and(fill) {
                    j += 1;
                }
                if at(first, j).is_some_and(fill) {
                    j += 1;
                    if at(first, j).is_some_and(frame) {
                        j += 1;
                    }
                    if gap(first, 2, 30) && at(first, j).is_some_and(|r| r.colour == background) {
                        continue;
                    }
                }
                let Some((i, leftmost)) = button(&runs, first + 1, background) else { continue };
                // the question is a window in the middle of the screen, its buttons from its
                // left edge: a row of controls in the right-hand panel is not it
                if !gap(i, 2, 30) || leftmost.start >= self.width / 2 {
                    continue;
                }
                let Some((i, middle)) = button(&runs, i + 1, background) else { continue };
                if !gap(i, 2, 30) {
                    continue;
                }
                let Some((i, _)) = button(&runs, i + 1, background) else { continue };
                if !gap(i, 2, usize::MAX)
                    || (gap(i, 2, 30) && button(&runs, i + 1, background).is_some_and(|(k, _)| gap(k, 1, usize::MAX)))
                {
                    continue;
                }
                let x = middle.start + 2;
                let bottom = (y..self.height).take_while(|&y| self.pixel(x, y) == middle.colour).last().unwrap_or(y);
                return Some((middle.start + middle.len / 2, (y + bottom) / 2));
            }
        }
        None
    }
}

/// `ppm` as `name` (PNG) in Cargo's temporary directory for integration tests.
fn save_png(ppm: &[u8], name: &str) -> PathBuf {
    let png = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let mut conv = Command::new("pnmtopng").stdin(Stdio::piped()).stdout(Stdio::piped()).spawn().unwrap();
    let mut stdin = conv.stdin.take().unwrap();
    let ppm = ppm.to_vec();
    let writer = std::thread::spawn(move || std::io::Write::write_all(&mut stdin, &ppm));
    let mut out = Vec::new();
    conv.stdout.take().unwrap().read_to_end(&mut out).unwrap();
    writer.join().unwrap().unwrap();
    conv.wait().unwrap();
    std::fs::write(&png, out).unwrap();
    png
}

/// Runs `program args` in `display` for at most [`TOOL`]: its stdout, or why it failed.
fn run(display: &str, program: &str, args: &[&str]) -> Result<String, String> {
    let what = format!("{program} {}", args.join(" "));
    let mut child = Command::new(program)
        .args(args)
        .env("DISPLAY", display)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("{what}: {e}"))?;
    let start = Instant::now();
    while child.try_wait().map_err(|e| e.to_string())?.is_none() {
        if start.elapsed() > TOOL {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!("{what}: no answer within {TOOL:?}"));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let out = child.wait_with_output().map_err(|e| e.to_string())?;
    if out.status.success() {
        Ok(String::from_utf8_lossy(&out.stdout).into_owned())
    } else {
        Err(format!("{what}: {}: {}", out.status, String::from_utf8_lossy(&out.stderr).trim()))
    }
}

/// Sends the window `argv[1]` a `WM_DELETE_WINDOW` client message, as a window manager's close
/// button does (and only if the window takes part in that protocol, as a window manager checks).
const CLOSE_REQUEST: &str = r#"
import sys
from Xlib import X, display, protocol
d = display.Display()
w = d.create_resource_object("window", int(sys.argv[1]))
wm_protocols = d.intern_atom("WM_PROTOCOLS")
delete = d.intern_atom("WM_DELETE_WINDOW")
if delete not in (w.get_wm_protocols() or []):
    sys.exit("the window does not list WM_DELETE_WINDOW in WM_PROTOCOLS")
message = protocol.event.ClientMessage(
    window=w, client_type=wm_protocols, data=(32, [delete, X.CurrentTime, 0, 0, 0])
)
w.send_event(message, event_mask=X.NoEventMask)
d.sync()
"#;

/// A python3 that has python3-xlib: the system's (apt installs it there), else the one on
/// `PATH`.
fn python_with_xlib() -> Option<String> {
    ["/usr/bin/python3", "python3"].into_iter().map(str::to_owned).find(|python| {
        Command::new(python)
            .args(["-c", "import Xlib"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    })
}

#[test]
fn the_editor_window_opens_under_xvfb_and_shows_both_views() {
    let _serial = ONE_AT_A_TIME.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    let missing: Vec<&str> =
        ["Xvfb", "xwd", "xwdtopnm", "pnmtopng"].into_iter().filter(|p| on_path(p).is_none()).collect();
    if !missing.is_empty() {
        eprintln!(
            "SKIPPED the_editor_window_opens_under_xvfb_and_shows_both_views: {} not installed \
             (apt install xvfb x11-apps netpbm; scripts/install-test-deps.sh tries to)",
            missing.join(", ")
        );
        return;
    }
    let (xvfb, display) = start_xvfb();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../splinekit-io/tests/data/swp/srev/wineglass.swp");
    let mut editor = Editor::start(&display, &file, "views");
    let (shot, light, surface) = editor.wait_for_both_views(&display);
    let png = save_png(&shot, "editor-window.png");
    eprintln!("screenshot: {} ({light} light 2D-view pixels, {surface} surface pixels)", png.display());
    assert!(light > 100_000, "the 2D view did not appear within {TIMEOUT:?} (see {})", png.display());
    assert!(surface > 20_000, "the 3D view shows no surface within {TIMEOUT:?} (see {})", png.display());
    let log = editor.log.clone();
    drop(editor);
    drop(xvfb);
    let _ = std::fs::remove_file(&log);
}

#[test]
fn closing_the_window_with_unsaved_changes_asks_first() {
    let _serial = ONE_AT_A_TIME.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    let name = "closing_the_window_with_unsaved_changes_asks_first";
    let mut missing: Vec<&str> =
        ["Xvfb", "xwd", "xwdtopnm", "pnmtopng", "xdotool"].into_iter().filter(|p| on_path(p).is_none()).collect();
    let python = python_with_xlib();
    if python.is_none() {
        missing.push("python3-xlib");
    }
    if !missing.is_empty() {
        eprintln!(
            "SKIPPED {name}: {} not installed (apt install xvfb x11-apps netpbm xdotool \
             python3-xlib; scripts/install-test-deps.sh tries to)",
            missing.join(", ")
        );
        return;
    }
    let python = python.unwrap();
    let begin = Instant::now();

    // 1. a copy of the file, opened; both views drawn
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("wineglass.swp");
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../splinekit-io/tests/data/swp/srev/wineglass.swp"),
        &file,
    )
    .unwrap();
    let original = std::fs::read(&file).unwrap();
    let unchanged = || std::fs::read(&file).unwrap() == original;
    let (_xvfb, display) = start_xvfb();
    let mut editor = Editor::start(&display, &file, "close");
    let (shot, light, surface) = editor.wait_for_both_views(&display);
    if light <= 100_000 || surface <= 20_000 {
        let png = save_png(&shot, "editor-close-start.png");
        editor.fail(&format!("the window did not show both views within {TIMEOUT:?} (see {})", png.display()));
    }

    // 2. focus (there is no window manager to give it), `s`: the title tells of changes
    let window = editor.window(&display);
    editor.tool(&display, "xdotool", &["windowfocus", "--sync", &window]);
    editor.tool(&display, "xdotool", &["key", "s"]);
    editor.wait_for_title(&display, &window, |t| t == "*wineglass.swp — splinekit", "*wineglass.swp — splinekit");
    let png = save_png(&screenshot(&display).expect("screenshot"), "editor-close-modified.png");
    eprintln!("screenshot with unsaved changes: {}", png.display());

    // 3. close as a window manager's close button does
    let asking = |image: &Image| image.middle_of_three_buttons().is_some() && image.views().0 < 1_000;
    editor.tool(&display, &python, &["-c", CLOSE_REQUEST, &window]);
    let asked = Instant::now();
    editor.wait_for_screen(&display, "the question shows", "editor-close-asked.png", asking);
    std::thread::sleep(Duration::from_secs(2).saturating_sub(asked.elapsed()));

    // 4. still there, still modified, the file untouched, the question drawn (the window
    // dimmed behind it, and a row of three buttons)
    editor.assert_running("after a close request with unsaved changes (it must ask first)");
    let title = editor.title(&display, &window);
    if !title.starts_with('*') {
        editor.fail(&format!("after the close request the title is {title:?}, without the leading *"));
    }
    if !unchanged() {
        editor.fail(&format!("the close request changed {}", file.display()));
    }
    let shot = screenshot(&display).expect("screenshot");
    let png = save_png(&shot, "editor-close-question.png");
    eprintln!("screenshot two seconds after the close request: {}", png.display());
    if !asking(&Image::parse_ppm(&shot).expect("xwdtopnm output")) {
        editor.fail(&format!("two seconds after the close request the question is gone (see {})", png.display()));
    }

    // 5. Escape cancels: the window stays as it was
    editor.tool(&display, "xdotool", &["key", "Escape"]);
    editor.wait_for_screen(&display, "Escape took the question away", "editor-close-cancelled.png", |image| {
        image.middle_of_three_buttons().is_none() && image.views().0 > 100_000
    });
    editor.assert_running("after Escape on the question");
    let title = editor.title(&display, &window);
    if !title.starts_with('*') || !unchanged() {
        editor.fail(&format!("after Escape on the question: title {title:?}, file unchanged: {}", unchanged()));
    }

    // close again and click Discard (the middle button): the editor ends, the file untouched
    editor.tool(&display, &python, &["-c", CLOSE_REQUEST, &window]);
    let image = editor.wait_for_screen(&display, "the question shows again", "editor-close-again.png", asking);
    let (x, y) = image.middle_of_three_buttons().expect("the buttons, found just before");
    editor.tool(&display, "xdotool", &["mousemove", "--sync", &x.to_string(), &y.to_string()]);
    std::thread::sleep(Duration::from_millis(300));
    editor.tool(&display, "xdotool", &["click", "1"]);
    let clicked = Instant::now();
    let status = loop {
        if let Some(status) = editor.child.0.try_wait().unwrap() {
            break status;
        }
        if clicked.elapsed() > ANSWER {
            let png = save_png(&screenshot(&display).expect("screenshot"), "editor-close-discard.png");
            editor.fail(&format!(
                "the editor still runs {ANSWER:?} after a click on Discard at ({x}, {y}) (see {})",
                png.display()
            ));
        }
        std::thread::sleep(Duration::from_millis(100));
    };
    if !status.success() || !unchanged() {
        editor.fail(&format!("after Discard the editor exited with {status}; file unchanged: {}", unchanged()));
    }
    eprintln!("{name}: {:.1} s", begin.elapsed().as_secs_f64());
    let log = editor.log.clone();
    drop(editor);
    let _ = std::fs::remove_file(&log);
}
