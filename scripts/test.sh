#!/usr/bin/env bash
# The project's test command (the README's second quick-start command): installs the system
# packages the editor's headless UI tests need (Mesa's software Vulkan driver), checks that
# the benchmarks build, then runs every test of the workspace, doc tests included, and the
# Python package's tests against the installed package (scripts/test-python.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-test-deps.sh
# winit warns without a runtime directory
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
# the editor keeps its recent files in the settings folder: the tests use a fresh one
export XDG_CONFIG_HOME="$(mktemp -d)"
cargo bench --workspace --locked --no-run
cargo test --workspace --locked
# the Python package: a venv under target/, pip install of crates/splinekit-py, pytest
bash scripts/test-python.sh
