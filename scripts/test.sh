#!/usr/bin/env bash
# The project's test command (the README's second quick-start command): checks that the
# benchmarks build, then runs every test of the workspace, doc tests included.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo bench --workspace --locked --no-run
cargo test --workspace --locked
