//! `splinekit-fuzz`: runs the fuzz harness for a number of cases or seconds and prints a
//! summary; exits with 1 when the oracle found anything (see the library docs).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;
use splinekit_fuzz::{Config, Format};

#[global_allocator]
static ALLOC: splinekit_fuzz::alloc::Counting = splinekit_fuzz::alloc::Counting;

/// Feed generated and mutated SWP, OBJ, PLY, STL and glb files to splinekit's readers and to
/// every command's library path, in-process; fail on a panic, an infinity or NaN in a
/// successful result, a written file that does not read back, or a case slower or bigger than
/// its bound (2 s + 50 µs per input byte, 256 MiB + 2000 bytes per input byte; the time ×10 in
/// a debug build).
#[derive(Debug, Parser)]
#[command(
    name = "splinekit-fuzz",
    after_help = "Examples:\n  \
    splinekit-fuzz --seconds 600\n  \
    splinekit-fuzz --seed 7 --cases 20000 --only swp --save-failures fuzz-failures\n  \
    splinekit-fuzz --seed 7 --case 1234 --save-failures fuzz-failures   (replay one case)\n  \
    splinekit-fuzz --input fuzz-failures/panic-7-1234.obj             (replay a saved input)"
)]
struct Args {
    /// Seed of the cases: the same seed gives the same inputs
    #[arg(long, default_value_t = 38)]
    seed: u64,
    /// Stop after this many seconds [default: 60 unless --cases is given]
    #[arg(long, value_name = "S")]
    seconds: Option<f64>,
    /// Stop after this many cases
    #[arg(long, value_name = "N")]
    cases: Option<u64>,
    /// Run only case N of the seed (a reproducer)
    #[arg(long, value_name = "N", conflicts_with_all = ["cases", "seconds"])]
    case: Option<u64>,
    /// Only inputs of this format
    #[arg(long, value_name = "FORMAT", value_parser = parse_format)]
    only: Option<Format>,
    /// Write each failing input (and with --case, the case's input) to this directory
    #[arg(long, value_name = "DIR")]
    save_failures: Option<PathBuf>,
    /// More seed files to mutate (directories, searched recursively)
    #[arg(long, value_name = "DIR")]
    corpus: Vec<PathBuf>,
    /// Feed this file instead (format from its extension), with 20 choices of options
    #[arg(long, value_name = "FILE", conflicts_with_all = ["cases", "seconds", "case"])]
    input: Option<PathBuf>,
    /// Multiply the time bound by this (slow or busy machines)
    #[arg(long, value_name = "F", default_value_t = 1.0)]
    time_scale: f64,
    /// No progress lines on standard error
    #[arg(long)]
    quiet: bool,
    /// Print each path of each case with the peak memory so far (to find what is slow or big)
    #[arg(long)]
    trace: bool,
    /// Fail the known findings (reported, not fixed yet) too
    #[arg(long)]
    strict: bool,
}

fn parse_format(text: &str) -> Result<Format, String> {
    Format::from_extension(text).ok_or_else(|| format!("expected swp, obj, ply, stl or glb, got {text:?}"))
}

fn main() -> ExitCode {
    let args = Args::parse();
    if let Some(path) = &args.input {
        return match splinekit_fuzz::harness::replay_file(path, 20) {
            Ok(findings) if findings.is_empty() => {
                println!("{}: no finding in 20 runs", path.display());
                ExitCode::SUCCESS
            }
            Ok(findings) => {
                for f in &findings {
                    println!("[{}] {}", f.kind, f.detail);
                }
                ExitCode::FAILURE
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            }
        };
    }
    let defaults = Config::default();
    let config = Config {
        seed: args.seed,
        cases: args.cases,
        seconds: args.seconds,
        only: args.only,
        case: args.case,
        save_failures: args.save_failures,
        corpus: args.corpus,
        time_base: defaults.time_base * args.time_scale,
        time_per_byte: defaults.time_per_byte * args.time_scale,
        progress: !args.quiet,
        trace: args.trace,
        strict: args.strict,
        ..defaults
    };
    let summary = splinekit_fuzz::run(&config);
    print!("{}", summary.report());
    if summary.failures.is_empty() { ExitCode::SUCCESS } else { ExitCode::FAILURE }
}
