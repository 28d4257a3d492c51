#!/usr/bin/env bash
# Builds Tumble and runs every test: the Rust workspace (unit, validation and CLI tests) and the
# doc tests. Needs only Rust (cargo) on the PATH; dependencies come from crates.io.
set -euo pipefail
cd "$(dirname "$0")"

echo "== cargo test (workspace) =="
cargo test --workspace --all-targets --locked
echo "== cargo test (doc tests) =="
cargo test --workspace --doc --locked
