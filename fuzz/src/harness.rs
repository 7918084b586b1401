//! The run loop: cases made from a seed, fed under `catch_unwind` with time and memory
//! measured, a watchdog for hangs, and the summary.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, Instant};

use crate::corpus::Corpus;
use crate::gen_mesh::{self, PlyEncoding};
use crate::rng::Rng;
use crate::{Finding, FindingKind, Format, Outcome, alloc, feed, gen_swp, mutate};

/// How much longer everything takes in a debug build (the time bound is multiplied by it).
pub const DEBUG_SLOWDOWN: f64 = 10.0;

/// What to run.
#[derive(Clone, Debug)]
pub struct Config {
    /// The seed: the same seed gives the same cases.
    pub seed: u64,
    /// Stop after this many cases.
    pub cases: Option<u64>,
    /// Stop after this many seconds (checked between cases).
    pub seconds: Option<f64>,
    /// Only this format.
    pub only: Option<Format>,
    /// Run only this case (a reproducer).
    pub case: Option<u64>,
    /// Write the input of every failing case here (and of the `case` before it runs).
    pub save_failures: Option<PathBuf>,
    /// More seed directories.
    pub corpus: Vec<PathBuf>,
    /// Time bound: this many seconds...
    pub time_base: f64,
    /// ...plus this many seconds per input byte.
    pub time_per_byte: f64,
    /// Memory bound: this many bytes of peak live heap...
    pub memory_base: usize,
    /// ...plus this many per input byte.
    pub memory_per_byte: usize,
    /// Abort a case that allocates past this many live bytes (so that it cannot take the
    /// machine's memory); a case between the bound and this is a failure like any other.
    pub memory_cap: usize,
    /// Stop the whole run when a case takes longer than this many times its time bound
    /// (at least 30 s): a hang.
    pub hang_factor: f64,
    /// Print a progress line to standard error every ten seconds.
    pub progress: bool,
    /// Print every path's name, peak memory so far to standard error ([`feed::set_trace`]).
    pub trace: bool,
    /// Fail the [`KNOWN`] findings too.
    pub strict: bool,
}

impl Default for Config {
    fn default() -> Self {
        let slowdown = if cfg!(debug_assertions) { DEBUG_SLOWDOWN } else { 1.0 };
        Self {
            seed: 38,
            cases: None,
            seconds: None,
            only: None,
            case: None,
            save_failures: None,
            corpus: Vec::new(),
            time_base: 2.0 * slowdown,
            time_per_byte: 50e-6 * slowdown,
            memory_base: 256 << 20,
            memory_per_byte: 2000,
            memory_cap: 6 << 30,
            hang_factor: 10.0,
            progress: false,
            trace: false,
            strict: false,
        }
    }
}

/// How an input was made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strategy {
    /// Structure-aware generation.
    Generated,
    /// A seed file with bytes mutated.
    Mutated,
    /// A generated file with bytes mutated.
    GeneratedMutated,
}

impl std::fmt::Display for Strategy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Generated => "generated",
            Self::Mutated => "mutated seed",
            Self::GeneratedMutated => "generated then mutated",
        })
    }
}

/// One input, ready to feed.
#[derive(Clone, Debug)]
pub struct Case {
    /// Its index in the run.
    pub index: u64,
    /// Its format.
    pub format: Format,
    /// How it was made.
    pub strategy: Strategy,
    /// Which seed file it mutates, if any.
    pub seed_file: Option<String>,
    /// The bytes.
    pub input: Vec<u8>,
    /// The random numbers the paths draw their options from.
    pub rng: Rng,
}

/// A generated file of `format`.
fn generate(format: Format, rng: &mut Rng) -> Vec<u8> {
    if format == Format::Swp {
        return gen_swp::generate(rng).into_bytes();
    }
    let m = gen_mesh::mesh(rng);
    match format {
        Format::Obj => gen_mesh::obj(rng, &m),
        Format::Ply => {
            let encoding = *rng.pick(&[PlyEncoding::Ascii, PlyEncoding::Little, PlyEncoding::Big]);
            gen_mesh::ply(rng, &m, encoding)
        }
        Format::Stl if rng.chance(0.5) => gen_mesh::stl_ascii(rng, &m),
        Format::Stl => gen_mesh::stl_binary(rng, &m),
        _ => gen_mesh::glb(rng, &m),
    }
}

/// Case `index` of a run with `seed`: its format (cycling through the formats, or `only`),
/// how it is made, its bytes.
pub fn make_case(seed: u64, index: u64, only: Option<Format>, corpus: &Corpus) -> Case {
    let format = only.unwrap_or(Format::ALL[(index % Format::ALL.len() as u64) as usize]);
    let mut rng = Rng::for_case(seed, index);
    let seeds = &corpus.seeds[format.index()];
    let roll = rng.unit();
    let (strategy, seed_file, input) = if roll < 0.45 || (seeds.is_empty() && roll < 0.85) {
        (Strategy::Generated, None, generate(format, &mut rng))
    } else if roll < 0.85 {
        let (name, bytes) = rng.pick(seeds).clone();
        let other = &rng.pick(seeds).1.clone();
        (Strategy::Mutated, Some(name), mutate::mutate(&mut rng, &bytes, other))
    } else {
        let bytes = generate(format, &mut rng);
        let other = generate(format, &mut rng);
        (Strategy::GeneratedMutated, None, mutate::mutate(&mut rng, &bytes, &other))
    };
    Case { index, format, strategy, seed_file, input, rng }
}

/// Counts for one format.
#[derive(Clone, Debug, Default)]
pub struct FormatStats {
    /// Cases run.
    pub cases: u64,
    /// Inputs the reader accepted.
    pub accepted: u64,
    /// Inputs the reader refused with an error.
    pub refused: u64,
    /// Refusals of text input whose error has no line and column.
    pub unlocated: u64,
    /// Accepted inputs with numbers so large that some result overflowed (refused by the
    /// commands).
    pub overflow: u64,
    /// Cases that failed the oracle.
    pub failures: u64,
    /// Input bytes fed.
    pub bytes: u64,
    /// The slowest case: seconds, index.
    pub slowest: (f64, u64),
    /// The case with the largest peak memory: bytes, index.
    pub biggest: (usize, u64),
    /// The largest share of its time bound a case used: share, index.
    pub time_share: (f64, u64),
    /// The largest share of its memory bound a case used: share, index.
    pub memory_share: (f64, u64),
}

/// One failing case.
#[derive(Clone, Debug)]
pub struct Failure {
    /// The case index.
    pub index: u64,
    /// Its format.
    pub format: Format,
    /// How it was made.
    pub strategy: Strategy,
    /// What the oracle found.
    pub finding: Finding,
    /// Seconds it took.
    pub seconds: f64,
    /// Its peak live heap, in bytes.
    pub peak: usize,
    /// Its input.
    pub input: Vec<u8>,
    /// Where the input was saved.
    pub saved: Option<PathBuf>,
}

/// What a run did.
#[derive(Clone, Debug, Default)]
pub struct Summary {
    /// The seed.
    pub seed: u64,
    /// Counts per format, in [`Format::ALL`] order.
    pub stats: [FormatStats; 5],
    /// Every failing case, in order.
    pub failures: Vec<Failure>,
    /// Cases with a [`KNOWN`] finding (not failed): index, format, finding.
    pub known: Vec<(u64, Format, Finding)>,
    /// A few text-reader errors without a position.
    pub unlocated_examples: Vec<String>,
    /// Seconds the run took.
    pub seconds: f64,
    /// Whether the counting allocator measured memory.
    pub memory_measured: bool,
    /// Seed files by format.
    pub seed_files: [usize; 5],
}

impl Summary {
    /// Cases run, all formats together.
    #[must_use]
    pub fn num_cases(&self) -> u64 {
        self.stats.iter().map(|s| s.cases).sum()
    }

    /// The failures grouped by kind and where (a panic's location, a finding's text with its
    /// numbers blanked): `(kind, signature) → indices into `failures``.
    #[must_use]
    pub fn groups(&self) -> BTreeMap<(FindingKind, String), Vec<usize>> {
        let mut groups: BTreeMap<(FindingKind, String), Vec<usize>> = BTreeMap::new();
        for (i, f) in self.failures.iter().enumerate() {
            groups.entry((f.finding.kind, signature(&f.finding))).or_default().push(i);
        }
        groups
    }

    /// The summary as text: a table per format, then every group of failures with a
    /// reproducer.
    #[must_use]
    pub fn report(&self) -> String {
        let mut s = String::new();
        let n = self.num_cases();
        let _ = writeln!(
            s,
            "splinekit-fuzz: seed {}, {n} cases in {:.1} s ({:.0} cases/s); memory {}; seed files (swp obj ply stl glb) {:?}",
            self.seed,
            self.seconds,
            n as f64 / self.seconds.max(1e-9),
            if self.memory_measured { "measured" } else { "not measured (no counting allocator)" },
            self.seed_files
        );
        let _ = writeln!(
            s,
            "{:<6} {:>8} {:>9} {:>8} {:>12} {:>9} {:>9} {:>9}  {:<22} {:<22} {:>16} {:>16}",
            "format",
            "cases",
            "accepted",
            "refused",
            "no line:col",
            "overflow",
            "failures",
            "MB fed",
            "slowest case",
            "most memory",
            "time/bound",
            "mem/bound"
        );
        for (format, st) in Format::ALL.iter().zip(&self.stats) {
            let _ = writeln!(
                s,
                "{:<6} {:>8} {:>9} {:>8} {:>12} {:>9} {:>9} {:>9.2}  {:<22} {:<22} {:>16} {:>16}",
                format.extension(),
                st.cases,
                st.accepted,
                st.refused,
                st.unlocated,
                st.overflow,
                st.failures,
                st.bytes as f64 / 1e6,
                format!("{:.3} s (#{})", st.slowest.0, st.slowest.1),
                format!("{:.1} MB (#{})", st.biggest.0 as f64 / 1e6, st.biggest.1),
                format!("{:.1}% (#{})", 100.0 * st.time_share.0, st.time_share.1),
                format!("{:.1}% (#{})", 100.0 * st.memory_share.0, st.memory_share.1),
            );
        }
        for example in &self.unlocated_examples {
            let _ = writeln!(s, "text-reader error without line:col: {example}");
        }
        for (kind, text, what) in KNOWN {
            let cases: Vec<String> = self
                .known
                .iter()
                .filter(|(_, _, f)| f.kind == kind && f.detail.contains(text))
                .map(|(i, format, _)| format!("#{i} ({format})"))
                .collect();
            if !cases.is_empty() {
                let _ = writeln!(
                    s,
                    "known, not failed: [{kind}] {what}: {} case(s): {}",
                    cases.len(),
                    cases.iter().take(8).cloned().collect::<Vec<_>>().join(", ")
                );
            }
        }
        let groups = self.groups();
        let _ = writeln!(s, "failures: {} cases in {} groups", self.failures.len(), groups.len());
        for ((kind, _), members) in &groups {
            let first = &self.failures[members[0]];
            let smallest = members.iter().map(|&i| &self.failures[i]).min_by_key(|f| f.input.len()).unwrap_or(first);
            let _ = writeln!(
                s,
                "\n[{kind}] {} case(s), first #{} ({}, {}): {}\n  smallest: #{} ({} bytes, {:.3} s, {:.1} MB); replay: splinekit-fuzz --seed {} --case {}{}",
                members.len(),
                first.index,
                first.format,
                first.strategy,
                first.finding.detail,
                smallest.index,
                smallest.input.len(),
                smallest.seconds,
                smallest.peak as f64 / 1e6,
                self.seed,
                smallest.index,
                smallest.saved.as_ref().map(|p| format!("; input saved as {}", p.display())).unwrap_or_default()
            );
            if smallest.input.len() <= 400 {
                let _ = writeln!(s, "  input: {:?}", String::from_utf8_lossy(&smallest.input));
            }
        }
        s
    }
}

/// A failure's group key: a panic's first line (its location), otherwise the detail with
/// every number (and `inf`, `NaN`) blanked, cut to 100 characters.
fn signature(f: &Finding) -> String {
    let text = if f.kind == FindingKind::Panic { f.detail.lines().next().unwrap_or("") } else { &f.detail };
    let text = text.replace("NaN", "0").replace("inf", "0");
    let mut out = String::new();
    let mut in_number = false;
    for c in text.chars() {
        let part = c.is_ascii_digit() || (in_number && matches!(c, '.' | 'e' | 'E' | '-' | '+'));
        if part && !in_number {
            out.push('#');
        } else if !part {
            out.push(c);
        }
        in_number = part;
    }
    out.replace("-#", "#").chars().take(100).collect()
}

/// Findings reported with issue #38 and not fixed yet, by kind and the start of their
/// text: `(kind, text, what it is)`. They are listed in the summary, not failed, unless
/// `strict`.
pub const KNOWN: [(FindingKind, &str, &str); 0] = [];

/// The known finding `finding` is, if any: its description.
fn known(finding: &Finding) -> Option<&'static str> {
    KNOWN.iter().find(|(kind, text, _)| *kind == finding.kind && finding.detail.contains(text)).map(|k| k.2)
}

/// Panic messages caught while a case runs (any thread: rayon's workers too).
static PANICS: Mutex<Vec<String>> = Mutex::new(Vec::new());
/// The case running, for the panic hook's line.
static LABEL: Mutex<String> = Mutex::new(String::new());

/// The panic hook while cases run: keeps the message for the report, and says it on standard
/// error with the case (a panic that cannot unwind aborts the process before any report).
fn hook(info: &std::panic::PanicHookInfo<'_>) {
    let label = LABEL.lock().unwrap_or_else(PoisonError::into_inner).clone();
    eprintln!("splinekit-fuzz: panic in {label}: {info}");
    PANICS.lock().unwrap_or_else(PoisonError::into_inner).push(info.to_string());
}

/// The case the watchdog watches.
struct Watch {
    /// Milliseconds since `origin` at which the current case started; `u64::MAX` between
    /// cases.
    started: AtomicU64,
    /// Its hang limit in milliseconds.
    limit: AtomicU64,
    /// Its label and input, for the report.
    current: Mutex<(String, Format, Vec<u8>)>,
    origin: Instant,
    done: AtomicBool,
    save: Option<PathBuf>,
}

impl Watch {
    fn now_ms(&self) -> u64 {
        self.origin.elapsed().as_millis() as u64
    }

    /// Runs until `done`: a case past its limit ends the process, after saying which.
    fn watch(&self) {
        while !self.done.load(Ordering::Relaxed) {
            std::thread::sleep(Duration::from_millis(200));
            let started = self.started.load(Ordering::Relaxed);
            if started == u64::MAX {
                continue;
            }
            let elapsed = self.now_ms().saturating_sub(started);
            if elapsed > self.limit.load(Ordering::Relaxed) {
                let (label, format, input) = &*self.current.lock().unwrap_or_else(PoisonError::into_inner);
                let saved = self.save.as_ref().and_then(|dir| save(dir, "hang", label, *format, input));
                eprintln!(
                    "\nsplinekit-fuzz: HANG: {label} still running after {:.1} s{}",
                    elapsed as f64 / 1000.0,
                    saved.map(|p| format!("; input saved as {}", p.display())).unwrap_or_default()
                );
                std::process::exit(3);
            }
        }
    }
}

/// Writes a failing input to `dir` as `KIND-LABEL.EXT`.
fn save(dir: &Path, kind: &str, label: &str, format: Format, input: &[u8]) -> Option<PathBuf> {
    std::fs::create_dir_all(dir).ok()?;
    let name: String = label.chars().map(|c| if c.is_ascii_alphanumeric() { c } else { '-' }).collect();
    let path = dir.join(format!("{kind}-{name}.{}", format.extension()));
    std::fs::write(&path, input).ok()?;
    Some(path)
}

/// Feeds one case under `catch_unwind`, measuring time and memory; the finding, if any.
fn run_one(case: &mut Case) -> (Result<Outcome, Finding>, f64, usize) {
    PANICS.lock().unwrap_or_else(PoisonError::into_inner).clear();
    alloc::reset_peak();
    let base = alloc::live();
    let start = Instant::now();
    let (format, input, rng) = (case.format, &case.input, &mut case.rng);
    let result = std::panic::catch_unwind(AssertUnwindSafe(|| feed::feed(format, input, rng)));
    let seconds = start.elapsed().as_secs_f64();
    let peak = alloc::peak().saturating_sub(base);
    let result = match result {
        Ok(r) => r,
        Err(payload) => {
            let caught = PANICS.lock().unwrap_or_else(PoisonError::into_inner).join("\n");
            let detail = if caught.is_empty() {
                payload
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| payload.downcast_ref::<&str>().map(|s| (*s).to_owned()))
                    .unwrap_or_else(|| "a panic without a message".into())
            } else {
                caught
            };
            Err(Finding::new(FindingKind::Panic, detail))
        }
    };
    (result, seconds, peak)
}

/// Runs the cases `config` asks for and returns what happened.
pub fn run(config: &Config) -> Summary {
    let corpus = Corpus::load(&config.corpus);
    feed::set_trace(config.trace);
    let mut summary = Summary {
        seed: config.seed,
        memory_measured: alloc::is_installed(),
        seed_files: corpus.counts(),
        ..Summary::default()
    };
    let watch = Arc::new(Watch {
        started: AtomicU64::new(u64::MAX),
        limit: AtomicU64::new(u64::MAX),
        current: Mutex::new((String::new(), Format::Swp, Vec::new())),
        origin: Instant::now(),
        done: AtomicBool::new(false),
        save: config.save_failures.clone(),
    });
    let watcher = {
        let watch = Arc::clone(&watch);
        std::thread::spawn(move || watch.watch())
    };
    let previous_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(hook));
    let start = Instant::now();
    let mut last_progress = Instant::now();
    let limit_seconds = match (config.cases, config.seconds, config.case) {
        (_, _, Some(_)) | (Some(_), None, _) => f64::INFINITY,
        (_, Some(s), _) => s,
        (None, None, _) => 60.0,
    };
    let (first, count) = match config.case {
        Some(i) => (i, 1),
        None => (0, config.cases.unwrap_or(u64::MAX)),
    };
    for index in first..first.saturating_add(count) {
        if start.elapsed().as_secs_f64() >= limit_seconds {
            break;
        }
        let mut case = make_case(config.seed, index, config.only, &corpus);
        let len = case.input.len();
        let label = format!("case {index} of seed {} ({}, {})", config.seed, case.format, case.strategy);
        if config.case.is_some()
            && let Some(dir) = &config.save_failures
            && let Some(path) = save(dir, "case", &format!("{}-{index}", config.seed), case.format, &case.input)
        {
            eprintln!("splinekit-fuzz: case {index} input written to {}", path.display());
        }
        let time_bound = config.time_base + config.time_per_byte * len as f64;
        let memory_bound = config.memory_base.saturating_add(config.memory_per_byte.saturating_mul(len));
        let replay = format!("{label}; replay: splinekit-fuzz --seed {} --case {index}", config.seed);
        alloc::set_label(&replay);
        *LABEL.lock().unwrap_or_else(PoisonError::into_inner) = replay;
        alloc::set_cap(alloc::live().saturating_add(config.memory_cap));
        *watch.current.lock().unwrap_or_else(PoisonError::into_inner) = (label, case.format, case.input.clone());
        watch.limit.store((1000.0 * (config.hang_factor * time_bound).max(30.0)) as u64, Ordering::Relaxed);
        watch.started.store(watch.now_ms(), Ordering::Relaxed);
        let (result, seconds, peak) = run_one(&mut case);
        watch.started.store(u64::MAX, Ordering::Relaxed);
        alloc::set_cap(usize::MAX);
        let (peak_path, slow_path) = feed::heaviest_paths();
        let result = result.and_then(|outcome| {
            if seconds > time_bound {
                Err(Finding::new(
                    FindingKind::Slow,
                    format!(
                        "{seconds:.2} s for {len} bytes, more than the bound of {time_bound:.2} s, most of it in: {slow_path}"
                    ),
                ))
            } else if peak > memory_bound {
                Err(Finding::new(
                    FindingKind::Memory,
                    format!(
                        "{:.1} MB peak for {len} bytes, more than the bound of {:.1} MB, reached in: {peak_path}",
                        peak as f64 / 1e6,
                        memory_bound as f64 / 1e6
                    ),
                ))
            } else {
                Ok(outcome)
            }
        });
        let result = match result {
            Err(finding) if !config.strict && known(&finding).is_some() => {
                summary.known.push((index, case.format, finding));
                Ok(Outcome::accepted())
            }
            other => other,
        };
        let st = &mut summary.stats[case.format.index()];
        st.cases += 1;
        st.bytes += len as u64;
        if seconds > st.slowest.0 {
            st.slowest = (seconds, index);
        }
        if peak > st.biggest.0 {
            st.biggest = (peak, index);
        }
        let time_share = seconds / time_bound;
        if time_share > st.time_share.0 {
            st.time_share = (time_share, index);
        }
        let memory_share = peak as f64 / memory_bound as f64;
        if memory_share > st.memory_share.0 {
            st.memory_share = (memory_share, index);
        }
        match result {
            Ok(outcome) => {
                if outcome.accepted {
                    st.accepted += 1;
                } else {
                    st.refused += 1;
                }
                st.overflow += u64::from(outcome.overflow);
                if !outcome.located {
                    st.unlocated += 1;
                    if summary.unlocated_examples.len() < 5 {
                        summary.unlocated_examples.push(format!(
                            "#{index} ({}): {}",
                            case.format,
                            outcome.message.unwrap_or_default()
                        ));
                    }
                }
            }
            Err(finding) => {
                st.failures += 1;
                let same = summary
                    .failures
                    .iter()
                    .filter(|f| f.finding.kind == finding.kind && signature(&f.finding) == signature(&finding))
                    .count();
                let saved = match &config.save_failures {
                    Some(dir) if same < 3 => save(
                        dir,
                        &finding.kind.to_string().replace(' ', "-"),
                        &format!("{}-{index}", config.seed),
                        case.format,
                        &case.input,
                    ),
                    _ => None,
                };
                if config.progress {
                    eprintln!("splinekit-fuzz: case {index} ({}): {}: {}", case.format, finding.kind, finding.detail);
                }
                summary.failures.push(Failure {
                    index,
                    format: case.format,
                    strategy: case.strategy,
                    finding,
                    seconds,
                    peak,
                    input: case.input,
                    saved,
                });
            }
        }
        if config.progress && last_progress.elapsed() >= Duration::from_secs(10) {
            last_progress = Instant::now();
            eprintln!(
                "splinekit-fuzz: {} cases, {} failures, {:.0} s",
                summary.num_cases(),
                summary.failures.len(),
                start.elapsed().as_secs_f64()
            );
        }
    }
    summary.seconds = start.elapsed().as_secs_f64();
    std::panic::set_hook(previous_hook);
    watch.done.store(true, Ordering::Relaxed);
    let _ = watcher.join();
    summary
}

/// Feeds the file at `path` (its format from its extension) `times` times, each with other
/// option choices; the findings.
///
/// # Errors
/// The file cannot be read or has no known extension.
pub fn replay_file(path: &Path, times: u64) -> Result<Vec<Finding>, String> {
    let format =
        Format::from_path(path).ok_or_else(|| format!("{}: not .swp, .obj, .ply, .stl or .glb", path.display()))?;
    let input = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let previous_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(hook));
    let mut findings = Vec::new();
    for k in 0..times {
        let mut case = Case {
            index: k,
            format,
            strategy: Strategy::Mutated,
            seed_file: None,
            input: input.clone(),
            rng: Rng::for_case(0, k),
        };
        if let (Err(f), _, _) = run_one(&mut case) {
            findings.push(f);
        }
    }
    std::panic::set_hook(previous_hook);
    Ok(findings)
}
