//! Long work off the UI thread: a [`Task`] runs a closure on its own thread, says how far it
//! got, and can be cancelled, while the window keeps drawing.
//!
//! Cancelling stops waiting at once: the result is dropped, and work that checks
//! [`Progress::is_cancelled`] between its steps stops at the next step (a library call that
//! cannot be interrupted finishes in the background first).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc::{Receiver, TryRecvError, channel};
use std::time::{Duration, Instant};

use eframe::egui;

/// How far a task got, and whether it was cancelled (given to the task's closure).
#[derive(Clone, Debug)]
pub struct Progress {
    done: Arc<AtomicUsize>,
    cancel: Arc<AtomicBool>,
}

impl Progress {
    /// Records one more step done.
    pub fn step(&self) {
        self.done.fetch_add(1, Ordering::Relaxed);
    }

    /// Whether the user cancelled: stop at the next convenient step.
    #[must_use]
    pub fn is_cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }
}

/// A closure running on its own thread.
#[derive(Debug)]
pub struct Task<T> {
    /// What it does, for the progress line (`Sweeping 5.2 M triangles`).
    pub label: String,
    /// Steps in all (0: unknown).
    pub total: usize,
    started: Instant,
    progress: Progress,
    rx: Receiver<T>,
}

impl<T: Send + 'static> Task<T> {
    /// Starts `work` on a new thread; `ctx` (if given) is asked to redraw when it finishes.
    pub fn spawn(
        label: impl Into<String>,
        total: usize,
        ctx: Option<egui::Context>,
        work: impl FnOnce(&Progress) -> T + Send + 'static,
    ) -> Self {
        let progress = Progress { done: Arc::default(), cancel: Arc::default() };
        let (tx, rx) = channel();
        let p = progress.clone();
        std::thread::Builder::new()
            .name("splinekit-editor-work".to_owned())
            .spawn(move || {
                let out = work(&p);
                // the receiver is gone if the task was dropped or cancelled
                let _ = tx.send(out);
                if let Some(ctx) = ctx {
                    ctx.request_repaint();
                }
            })
            .expect("spawn a worker thread");
        Self { label: label.into(), total, started: Instant::now(), progress, rx }
    }
}

impl<T> Task<T> {
    /// The result once there is one (`None` while the work runs; an error if it stopped
    /// without one, which only a bug in it can do).
    pub fn poll(&mut self) -> Option<Result<T, String>> {
        match self.rx.try_recv() {
            Ok(out) => Some(Ok(out)),
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => Some(Err(format!("{} stopped without a result", self.label))),
        }
    }

    /// Asks the work to stop; the caller drops the task.
    pub fn cancel(&self) {
        self.progress.cancel.store(true, Ordering::Relaxed);
    }

    /// The fraction done, if the total is known.
    #[must_use]
    pub fn fraction(&self) -> Option<f32> {
        (self.total > 0).then(|| (self.progress.done.load(Ordering::Relaxed) as f32 / self.total as f32).min(1.0))
    }

    /// How long it has been running.
    #[must_use]
    pub fn elapsed(&self) -> Duration {
        self.started.elapsed()
    }

    /// Draws the progress line: a spinner or bar, the label, the time, and `Cancel`; returns
    /// whether Cancel was clicked. Asks for the next frame (20 a second), so the time moves.
    pub fn ui(&self, ui: &mut egui::Ui) -> bool {
        let mut cancel = false;
        ui.horizontal(|ui| {
            match self.fraction() {
                Some(f) => {
                    ui.add(egui::ProgressBar::new(f).desired_width(80.0).show_percentage());
                }
                None => {
                    spinner(ui, self.elapsed());
                }
            }
            ui.label(format!("{}… {:.1} s", self.label, self.elapsed().as_secs_f64()));
            cancel = ui.button("Cancel").clicked();
        });
        ui.ctx().request_repaint_after(Duration::from_millis(50));
        cancel
    }
}

/// An arc turning with `elapsed` time (egui's spinner asks for every frame at once; this one
/// is redrawn with the 20-a-second repaints of [`Task::ui`]).
fn spinner(ui: &mut egui::Ui, elapsed: Duration) {
    let size = ui.spacing().interact_size.y;
    let (rect, _) = ui.allocate_exact_size(egui::vec2(size, size), egui::Sense::hover());
    let t = elapsed.as_secs_f64() * 4.0;
    let radius = 0.4 * rect.height();
    let points: Vec<egui::Pos2> = (0..=24)
        .map(|i| {
            let a = t + f64::from(i) / 24.0 * 4.5;
            rect.center() + radius * egui::vec2(a.cos() as f32, a.sin() as f32)
        })
        .collect();
    ui.painter().add(egui::Shape::line(points, egui::Stroke::new(2.0, ui.visuals().strong_text_color())));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_task_reports_progress_and_its_result() {
        let mut t = Task::spawn("counting", 4, None, |p| {
            for _ in 0..4 {
                p.step();
            }
            7
        });
        let start = Instant::now();
        let out = loop {
            if let Some(out) = t.poll() {
                break out.unwrap();
            }
            assert!(start.elapsed() < Duration::from_secs(10));
            std::thread::sleep(Duration::from_millis(1));
        };
        assert_eq!(out, 7);
        assert_eq!(t.fraction(), Some(1.0));
    }

    #[test]
    fn a_cancelled_task_stops_at_its_next_step() {
        let (tx, rx) = channel();
        let t = Task::spawn("waiting", 0, None, move |p| {
            let start = Instant::now();
            while !p.is_cancelled() && start.elapsed() < Duration::from_secs(10) {
                std::thread::sleep(Duration::from_millis(1));
            }
            tx.send(p.is_cancelled()).unwrap();
        });
        t.cancel();
        assert!(rx.recv_timeout(Duration::from_secs(10)).unwrap());
    }
}
