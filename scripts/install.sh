#!/usr/bin/env bash
# Installs everything syssimx needs on Debian and builds it: the system packages, a virtual
# environment in .venv with the Python dependencies, and syssimx itself (pip builds the C engine
# and the FMUs with meson; the build directory is kept in build/release for `meson test`).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }

# clang and its runtimes: the fuzz target of the modelDescription reader (scripts/fuzz.sh);
# chromium: the documentation opened in a browser (scripts/check-docs-browser.py);
# libjs-mathjax and fonts-mathjax: the MathJax the documentation carries (docs/_ext)
apt_packages=(build-essential pkg-config libsundials-dev graphviz python3-venv clang
              libclang-rt-14-dev chromium libjs-mathjax fonts-mathjax)
missing=()
for package in "${apt_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" \
    || missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing Debian packages: ${missing[*]}"
  as_root apt-get update -qq
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
fi

python=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  echo "== creating the virtual environment .venv"
  "$python" -m venv .venv
fi
# meson-python runs the meson and ninja it finds first on PATH: the ones of the venv.
export PATH="$root/.venv/bin:$PATH"
echo "== installing the Python dependencies"
.venv/bin/python -m pip install -q --disable-pip-version-check --upgrade pip
.venv/bin/python -m pip install -q --disable-pip-version-check -r scripts/requirements.txt

# Before 0.5.0 this project was installed under the distribution name "syssimx", which is
# SysSimX's on PyPI; a virtual environment made by an older checkout still has it
if .venv/bin/python -m pip show syssimx 2>/dev/null | grep -qx "Version: 0.1.0"; then
  echo "== removing this project's old distribution 'syssimx' 0.1.0"
  .venv/bin/python -m pip uninstall -y -q syssimx
fi

echo "== building and installing syssimx (distribution syssimx-engine)"
.venv/bin/python -m pip install -q --disable-pip-version-check --no-build-isolation \
  -Cbuild-dir=build/release .
