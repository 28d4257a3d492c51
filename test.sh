#!/usr/bin/env bash
# Builds Tumble and runs every test: the Rust workspace (unit, validation and CLI tests), the doc
# tests, and the Python package's pytest suite. Needs Rust (cargo) and Python 3 with venv on the
# PATH; dependencies come from crates.io and PyPI. TUMBLE_SKIP_PYTHON=1 skips the Python part.
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
