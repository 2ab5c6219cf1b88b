#!/usr/bin/env bash
# The one test command (README, .ci/run): the Rust suites, then the Python package's pytest
# suite against a fresh build of the package installed into a throwaway virtual environment.
#
#   bash scripts/test.sh            # everything
#   SCREWDYN_SKIP_RUST=1 bash scripts/test.sh   # only the Python suite
#
# The package is installed exactly as a user would (`pip install ./crates/screwdyn-py`, maturin
# fetched by pip as the build backend), but built with the `py-test` profile (optimised, no fat
# LTO) through MATURIN_PEP517_ARGS: the release profile's fat LTO costs minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."

if [[ -z "${SCREWDYN_SKIP_RUST:-}" ]]; then
    cargo test --workspace
fi

PYTHON="${PYTHON:-python3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
if ! "$PYTHON" -m venv "$work/venv" 2>/dev/null; then
    # Debian's python3 ships venv separately.
    (apt-get update -qq && apt-get install -y -qq python3-venv) >/dev/null
    "$PYTHON" -m venv "$work/venv"
fi
py="$work/venv/bin/python"
MATURIN_PEP517_ARGS="--profile py-test" \
    "$py" -m pip install -q --disable-pip-version-check "./crates/screwdyn-py[test]"

set +e
"$py" -m pytest -q -p no:cacheprovider crates/screwdyn-py/tests
rc=$?
set -e
if [[ $rc -eq 5 ]]; then
    echo "pytest collected no tests: that is a failure" >&2
    exit 1
fi
exit $rc
