#!/usr/bin/env bash
# Builds Tumble and runs every test: the Rust workspace (unit, validation and CLI tests), the doc
# tests, the Python package's pytest suite, and the viewer's browser tests with the glTF validator
# (viewer/run_tests.sh). Needs Rust (cargo), Python 3 with venv, and Node.js with npm on the PATH;
# dependencies come from crates.io, PyPI, npm and (Chromium, when missing and run as root) apt.
# TUMBLE_SKIP_PYTHON=1 skips the Python part, TUMBLE_SKIP_VIEWER=1 the browser part.
set -euo pipefail
cd "$(dirname "$0")"

# tumble-py is a Python extension: it is built by maturin and tested from Python (below), not by
# cargo test, which would link it against libpython.
echo "== cargo test (workspace) =="
cargo test --workspace --exclude tumble-py --all-targets --locked
echo "== cargo test (doc tests) =="
cargo test --workspace --exclude tumble-py --doc --locked
if [ "${TUMBLE_SKIP_PYTHON:-0}" != 1 ]; then
    echo "== pytest (crates/tumble-py) =="
    crates/tumble-py/run_tests.sh
fi
if [ "${TUMBLE_SKIP_VIEWER:-0}" != 1 ]; then
    echo "== viewer: browser tests and glTF validator (viewer/run_tests.sh) =="
    viewer/run_tests.sh
fi
