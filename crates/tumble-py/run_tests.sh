#!/usr/bin/env bash
# Builds and installs the Python package into a virtual environment under target/ and runs its
# pytest suite. Needs only Rust (cargo) and Python 3 with venv; pip fetches maturin, numpy and
# pytest from PyPI. Extra arguments go to pytest (e.g. `-k arrays`).
#
#   crates/tumble-py/run_tests.sh
#
# The venv is kept between runs (target/py-venv); the Rust build reuses target/ too.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
venv="$root/target/py-venv"
python="${PYTHON:-python3}"

if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --upgrade pip
# The package's own pyproject: maturin builds the extension (release), [test] adds pytest + numpy.
"$venv/bin/python" -m pip install --disable-pip-version-check "$here[test]"
cd "$here"
"$venv/bin/python" -m pytest tests "$@"
