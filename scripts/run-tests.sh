#!/usr/bin/env bash
# Installs and builds syssimx, then runs every test: the C tests (meson test) in the release
# build and again under AddressSanitizer, a bounded fuzz run of the modelDescription reader,
# the linter, the documentation build (warnings are errors, every notebook executed) and its
# check in a browser, and the Python tests (pytest, which also runs the examples of the
# documentation's Markdown pages).
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
# UBSan stops at its first report: undefined behaviour is a failure, not a line in a log
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
  meson test -C build/asan --print-errorlogs

echo "== fuzz the modelDescription reader (${FUZZ_SECONDS:-90} s) and the plan reader (${PLAN_FUZZ_SECONDS:-60} s) (libFuzzer, ASan, UBSan)"
bash "$root/scripts/fuzz.sh"

echo "== pytest memory tests (AddressSanitizer engine and FMUs)"
# Python itself is not instrumented: the sanitizer runtimes are preloaded, Python's own
# allocations are not reported as leaks, and freed memory is filled so that an array still
# reading it shows wrong values. The resident-size test is left out: the sanitizer keeps freed
# memory in quarantine.
meson compile -C build/asan >/dev/null
LD_PRELOAD="$(gcc -print-file-name=libasan.so) $(gcc -print-file-name=libubsan.so)" \
  ASAN_OPTIONS=detect_leaks=0:max_free_fill_size=1048576 SYSSIMX_BUILD_DIR=build/asan \
  PYTHONPATH="$root/python" python -m pytest -q -p no:cacheprovider \
  tests/python/test_memory_*.py -k "not resident"

echo "== ruff"
ruff check python tests examples benchmarks

echo "== documentation"
# A fresh build: Sphinx reports a page's warnings only when it reads the page. Internal links
# are checked (-n); links to the web are not (no network here).
rm -rf build/docs docs/api/generated
python -m sphinx -W --keep-going -n -q -b html docs build/docs/html

echo "== documentation in headless Chromium"
# every page without console errors and with its images, the search, the tutorials' figures,
# maths typeset offline; skipped with a message where no Chromium is installed
python scripts/check-docs-browser.py build/docs/html

echo "== pytest"
# pytest exits 5 when it collected nothing: that is a failure here too.
# The test fixtures (tests/fmus) are never installed: the tests take them from the build.
status=0
SYSSIMX_FIXTURE_FMUS="$root/build/release/models" python -m pytest -q || status=$?
if [ "$status" -eq 5 ]; then echo "pytest collected no tests" >&2; exit 1; fi
exit "$status"
