#!/usr/bin/env bash
# The project's test command (the README's second quick-start command): sets up what the
# tests need, then runs every test of the workspace, the doc tests included, and checks
# that the benchmarks build.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace --locked
cargo bench --workspace --locked --no-run
