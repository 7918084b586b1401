//! Smoke test of the real editor window: `splinekit edit wineglass.swp` under a virtual X
//! server (Xvfb), screenshot with `xwd`, converted with netpbm. Checks that the window shows
//! both views (the 2D view's light background and the 3D view's lit surface) and saves the
//! screenshot as `editor-window.png` in Cargo's temporary directory for integration tests.
//!
//! Needs the apt packages `xvfb x11-apps netpbm` (scripts/install-test-deps.sh installs them);
//! where they are missing, the test prints why and passes without running.

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// How long the window may take to show both views (a cold software renderer is slow).
const TIMEOUT: Duration = Duration::from_secs(120);

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

#[test]
fn the_editor_window_opens_under_xvfb_and_shows_both_views() {
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

    let runtime = std::env::temp_dir().join(format!("splinekit-xdg-{}", std::process::id()));
    std::fs::create_dir_all(&runtime).unwrap();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../splinekit-io/tests/data/swp/srev/wineglass.swp");
    let log = std::env::temp_dir().join(format!("splinekit-edit-{}.log", std::process::id()));
    let mut editor = Killed(
        Command::new(env!("CARGO_BIN_EXE_splinekit"))
            .arg("edit")
            .arg(&file)
            .env("DISPLAY", &display)
            .env("XDG_RUNTIME_DIR", &runtime)
            .env_remove("WAYLAND_DISPLAY")
            .stdout(Stdio::null())
            .stderr(std::fs::File::create(&log).unwrap())
            .spawn()
            .expect("start splinekit edit"),
    );

    let start = Instant::now();
    let (shot, light, surface) = loop {
        if let Some(status) = editor.0.try_wait().unwrap() {
            panic!(
                "the editor exited ({status}) before showing its window:\n{}",
                std::fs::read_to_string(&log).unwrap()
            );
        }
        let bytes = screenshot(&display).expect("screenshot");
        let image = Image::parse_ppm(&bytes).expect("xwdtopnm output");
        assert_eq!((image.width, image.height), (1280, 800));
        // the 2D view's background (grey 250) on the left, the lit glass (grey-blue, blue
        // above red, brighter than the 3D view's dark background) on the right
        let light = image.count(0, 800, |[r, g, b]| r == 250 && g == 250 && b == 250);
        let surface = image.count(800, 1280, |[r, g, b]| {
            b > 110 && i32::from(b) - i32::from(r) >= 20 && g > r && b > g && i32::from(b) - i32::from(g) < 60
        });
        if (light > 100_000 && surface > 20_000) || start.elapsed() > TIMEOUT {
            break (bytes, light, surface);
        }
        std::thread::sleep(Duration::from_millis(500));
    };
    let png = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("editor-window.png");
    let mut conv = Command::new("pnmtopng").stdin(Stdio::piped()).stdout(Stdio::piped()).spawn().unwrap();
    let mut stdin = conv.stdin.take().unwrap();
    let writer = std::thread::spawn(move || std::io::Write::write_all(&mut stdin, &shot));
    let mut out = Vec::new();
    conv.stdout.take().unwrap().read_to_end(&mut out).unwrap();
    writer.join().unwrap().unwrap();
    conv.wait().unwrap();
    std::fs::write(&png, out).unwrap();
    eprintln!("screenshot: {} ({light} light 2D-view pixels, {surface} surface pixels)", png.display());
    assert!(light > 100_000, "the 2D view did not appear within {TIMEOUT:?} (see {})", png.display());
    assert!(surface > 20_000, "the 3D view shows no surface within {TIMEOUT:?} (see {})", png.display());
    drop(editor);
    drop(xvfb);
    let _ = std::fs::remove_dir_all(&runtime);
    let _ = std::fs::remove_file(&log);
}
