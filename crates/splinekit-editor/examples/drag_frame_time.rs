//! Frame times of the editor while a surface of about 5 million triangles is opened and a
//! point of its profile is dragged (#36): the whole editor, headless, rendered by wgpu (on
//! this machine Mesa's software rasterizer), one frame per step as a window would draw them.
//!
//! ```sh
//! cargo run --release -p splinekit-editor --example drag_frame_time
//! ```
//!
//! Prints the time of each phase's frames: opening (the worker sweeps; frames keep coming),
//! the frame that shows the whole surface, the frames of a drag (a preview of at most
//! 200 000 triangles), and the sweep after the release.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use eframe::egui::{Event, Modifiers, PointerButton, Vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use splinekit_editor::EditorApp;

/// The course's wineglass with 80 steps a profile segment and 1 500 slices: 5.5 M triangles.
fn big_glass() -> PathBuf {
    let src = concat!(env!("CARGO_MANIFEST_DIR"), "/../splinekit-io/tests/data/swp/srev/wineglass.swp");
    let text = std::fs::read_to_string(src).expect("bundled wineglass");
    let text = text.replacen("bsp2 profile 8 26", "bsp2 profile 80 26", 1).replacen(
        "srev wineglass 90",
        "srev wineglass 1500",
        1,
    );
    let path = std::env::temp_dir().join(format!("splinekit-drag-frame-time-{}.swp", std::process::id()));
    std::fs::write(&path, text).expect("write the test file");
    path
}

/// Summary of frame times: count, median, worst.
fn summary(name: &str, frames: &[Duration]) {
    if frames.is_empty() {
        println!("{name:<40} no frames");
        return;
    }
    let mut ms: Vec<f64> = frames.iter().map(|d| d.as_secs_f64() * 1e3).collect();
    ms.sort_by(f64::total_cmp);
    let median = ms[ms.len() / 2];
    let worst = ms[ms.len() - 1];
    println!("{name:<40} {:>4} frames   median {median:>7.1} ms   worst {worst:>7.1} ms", ms.len());
}

fn step(h: &mut Harness<'static, EditorApp>) -> Duration {
    let t = Instant::now();
    h.step();
    t.elapsed()
}

fn main() {
    let path = big_glass();
    let t0 = Instant::now();
    let app = EditorApp::new(Some(&path));
    let open = t0.elapsed();
    let mut h = Harness::builder().with_size(Vec2::new(1280.0, 800.0)).wgpu().build_eframe(move |_cc| app);
    println!("opening the file (parse, before the first frame): {:.1} ms", open.as_secs_f64() * 1e3);

    // frames while the worker sweeps the whole surface
    let mut sweeping = Vec::new();
    let start = Instant::now();
    while h.state().is_sweeping() || h.state().view3d.num_triangles() == 0 {
        sweeping.push(step(&mut h));
        std::thread::sleep(Duration::from_millis(10));
        assert!(start.elapsed() < Duration::from_secs(300), "the sweep did not finish in 5 minutes");
    }
    let full = h.state().view3d.num_triangles();
    let first_full = sweeping.pop().unwrap_or_default();
    println!("whole surface: {full} triangles, shown {:.2} s after the first frame", start.elapsed().as_secs_f64());
    summary("frames while sweeping (worker thread)", &sweeping);
    println!("{:<40} {:>7.1} ms", "the frame that shows the whole surface", first_full.as_secs_f64() * 1e3);
    let mut idle = Vec::new();
    for _ in 0..3 {
        idle.push(step(&mut h));
    }
    summary("frames after (nothing changes)", &idle);

    // a drag of a profile point, one pointer move a frame
    let from = h.get_by_label("P5").rect().center();
    h.event(Event::PointerMoved(from));
    h.event(Event::PointerButton {
        pos: from,
        button: PointerButton::Primary,
        pressed: true,
        modifiers: Modifiers::NONE,
    });
    let mut drag = vec![step(&mut h)];
    let mut last = from;
    for k in 1..=40 {
        last = from + Vec2::new(0.0, k as f32);
        h.event(Event::PointerMoved(last));
        drag.push(step(&mut h));
    }
    let shown = h.state().view3d.num_triangles();
    for (k, d) in drag.iter().enumerate().filter(|(_, d)| d.as_millis() > 200) {
        println!("  slow drag frame {k}: {:.1} ms", d.as_secs_f64() * 1e3);
    }
    summary(&format!("frames of the drag ({shown} triangles shown)"), &drag);
    h.event(Event::PointerButton {
        pos: last,
        button: PointerButton::Primary,
        pressed: false,
        modifiers: Modifiers::NONE,
    });
    let released = Instant::now();
    let mut after = Vec::new();
    while h.state().view3d.num_triangles() != full || h.state().is_sweeping() {
        after.push(step(&mut h));
        std::thread::sleep(Duration::from_millis(10));
        assert!(released.elapsed() < Duration::from_secs(300), "the sweep after the release did not finish");
    }
    let last_frame = after.pop().unwrap_or_default();
    println!("after the release: the whole surface again {:.2} s later", released.elapsed().as_secs_f64());
    summary("frames while sweeping again", &after);
    println!("{:<40} {:>7.1} ms", "the frame that shows it", last_frame.as_secs_f64() * 1e3);
    let _ = std::fs::remove_file(path);
}
