#!/usr/bin/env bash
# The one test command (README, .ci/run): the Rust suites, then the Python package's pytest
# suite, on a fresh machine.
#
#   bash scripts/test.sh                        # everything
#   SCREWDYN_SKIP_RUST=1 bash scripts/test.sh   # only the Python suite (still builds the extension)
#
# One build serves both suites: `cargo build --workspace --lib --bins --tests --examples` compiles every crate
# once, in the test profile, with the Python extension's `extension-module` feature, so the
# libraries, the CLI, the test binaries and the extension (`lib_screwdyn.so`) share their
# dependencies; `cargo test` then only runs. The package is assembled from that build the way
# maturin lays out its mixed Rust/Python package (`python/screwdyn/` plus the native module
# `screwdyn/_screwdyn.abi3.so`) and put on a throwaway virtual environment's path, whose test
# dependencies (the `test` extra of crates/screwdyn-py/pyproject.toml) download while cargo
# compiles. The user's route, `pip install ./crates/screwdyn-py`, builds the same sources with
# maturin in the release profile.
#
# Needs: cargo, python3 >= 3.10 with venv, PyPI, and Chromium for the `screwdyn view` tests
# (/usr/bin/chromium or $SCREWDYN_CHROMIUM; installed here with apt-get on Debian when run as root).
set -euo pipefail
cd "$(dirname "$0")/.."

say() { printf 'test.sh: %s\n' "$*" >&2; }
die() { say "$*"; exit 2; }

# Prerequisites, checked before anything is built.
PYTHON="${PYTHON:-python3}"
command -v cargo >/dev/null || die "cargo is not on PATH: install Rust from https://rustup.rs"
command -v "$PYTHON" >/dev/null || die "$PYTHON is not on PATH: the Python suite needs Python >= 3.10"
"$PYTHON" -c 'import sys; sys.exit(sys.version_info < (3, 10))' \
    || die "$("$PYTHON" --version) is too old: the Python suite needs Python >= 3.10"
chromium="${SCREWDYN_CHROMIUM:-/usr/bin/chromium}"
if [[ ! -x "$chromium" ]]; then
    if [[ $EUID -eq 0 ]] && command -v apt-get >/dev/null; then
        say "installing Debian's chromium for the 'screwdyn view' tests"
        (apt-get update -qq && apt-get install -y -qq chromium) >/dev/null
    else
        die "the 'screwdyn view' tests need Chromium at $chromium (Debian: apt-get install chromium; or set SCREWDYN_CHROMIUM=/path/to/chromium)"
    fi
fi
export SCREWDYN_CHROMIUM="$chromium"

# The Python environment, filled in the background while cargo compiles.
work="$(mktemp -d)"
pip_pid=""
cleanup() {
    [[ -n "$pip_pid" ]] && kill "$pip_pid" 2>/dev/null
    rm -rf "$work"
}
trap cleanup EXIT
if ! "$PYTHON" -m venv "$work/venv" 2>/dev/null; then
    if [[ $EUID -eq 0 ]] && command -v apt-get >/dev/null; then
        (apt-get update -qq && apt-get install -y -qq python3-venv) >/dev/null
        "$PYTHON" -m venv "$work/venv"
    else
        die "$PYTHON -m venv failed: install Python's venv module (Debian: apt-get install python3-venv)"
    fi
fi
py="$work/venv/bin/python"
(
    # pyproject.toml is read with tomllib (Python >= 3.11) or its backport.
    "$py" -c 'import tomllib' 2>/dev/null \
        || "$py" -m pip install -q --disable-pip-version-check tomli >/dev/null 2>&1 || true
    "$py" - <<'EOF' >"$work/requirements.txt"
try:
    import tomllib
except ImportError:
    import tomli as tomllib
with open("crates/screwdyn-py/pyproject.toml", "rb") as f:
    project = tomllib.load(f)["project"]
print("\n".join(project["dependencies"] + project["optional-dependencies"]["test"]))
EOF
    "$py" -m pip install -q --disable-pip-version-check -r "$work/requirements.txt"
) >"$work/pip.log" 2>&1 &
pip_pid=$!

# One build for both suites (every target `cargo test` runs; benches are left to the bench
# scripts), then the Rust tests.
features=(--features screwdyn-py/extension-module)
cargo build --workspace --lib --bins --tests --examples "${features[@]}"
if [[ -z "${SCREWDYN_SKIP_RUST:-}" ]]; then
    cargo test --workspace "${features[@]}"
fi

# The package, assembled from the build above.
so="target/debug/lib_screwdyn.so"
[[ -f "$so" ]] || die "$so was not built"
mkdir -p "$work/pkg"
cp -r crates/screwdyn-py/python/screwdyn "$work/pkg/"
cp "$so" "$work/pkg/screwdyn/_screwdyn.abi3.so"
"$py" -c 'import site; print(site.getsitepackages()[0])' | {
    read -r site_dir
    echo "$work/pkg" >"$site_dir/screwdyn-test.pth"
}
if ! wait "$pip_pid"; then
    pip_pid=""
    cat "$work/pip.log" >&2
    die "installing the Python test dependencies failed (log above)"
fi
pip_pid=""

set +e
"$py" -m pytest -q -p no:cacheprovider crates/screwdyn-py/tests
rc=$?
set -e
if [[ $rc -eq 5 ]]; then
    say "pytest collected no tests: that is a failure"
    exit 1
fi
exit $rc
