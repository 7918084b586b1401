//! The fuzz harness for about a minute on a fixed seed (`.ci/run` runs it with the other
//! tests): a fixed number of cases, so the run is the same on every machine. Tests build in
//! debug mode, where a case takes about ten times longer than in release; run the fuzzer
//! longer with `cargo run --release -p splinekit-fuzz -- --seconds 600`.

use splinekit_fuzz::{Config, Format};

#[global_allocator]
static ALLOC: splinekit_fuzz::alloc::Counting = splinekit_fuzz::alloc::Counting;

/// The fixed seed of the CI run.
const SEED: u64 = 38;
/// Cases of the CI run: about 45–60 s in the test profile on a 2-core machine.
const CASES: u64 = 9000;

#[test]
fn fuzz_fixed_seed() {
    let config = Config { seed: SEED, cases: Some(CASES), ..Config::default() };
    let summary = splinekit_fuzz::run(&config);
    let report = summary.report();
    println!("{report}");
    assert_eq!(summary.num_cases(), CASES, "{report}");
    assert!(summary.memory_measured, "the counting allocator is not installed");
    for format in Format::ALL {
        let st = &summary.stats[format.index()];
        assert!(st.accepted > 0 && st.refused > 0, "{format}: no accepted or no refused input\n{report}");
    }
    assert!(summary.failures.is_empty(), "the fuzzer found something; reproduce with the replay line\n{report}");
}
