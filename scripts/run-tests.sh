#!/usr/bin/env bash
# Installs and builds syssimx, then runs every test: the C tests (meson test) in the release
# build and again under AddressSanitizer, the Python tests (pytest) and the linter.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/install.sh"
cd "$root"
export PATH="$root/.venv/bin:$PATH"

echo "== meson test (release build)"
meson test -C build/release --print-errorlogs

echo "== meson test (AddressSanitizer)"
if [ ! -f build/asan/build.ninja ]; then
  meson setup build/asan -Db_sanitize=address,undefined -Db_lundef=false --buildtype=debug >/dev/null
fi
ASAN_OPTIONS=detect_leaks=1 meson test -C build/asan --print-errorlogs

echo "== ruff"
ruff check python tests examples benchmarks

echo "== pytest"
# pytest exits 5 when it collected nothing: that is a failure here too.
status=0
python -m pytest -q || status=$?
if [ "$status" -eq 5 ]; then echo "pytest collected no tests" >&2; exit 1; fi
exit "$status"
