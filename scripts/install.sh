#!/usr/bin/env bash
# Installs everything syssimx needs on Debian and builds it: the system packages, a virtual
# environment in .venv with the Python dependencies, and syssimx itself (pip builds the C engine
# and the FMUs with meson; the build directory is kept in build/release for `meson test`).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }

# clang and its runtimes: the fuzz target of the modelDescription reader (scripts/fuzz.sh)
apt_packages=(build-essential pkg-config libsundials-dev graphviz python3-venv clang
              libclang-rt-14-dev)
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

echo "== building and installing syssimx"
.venv/bin/python -m pip install -q --disable-pip-version-check --no-build-isolation \
  -Cbuild-dir=build/release .
