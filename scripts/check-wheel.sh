#!/usr/bin/env bash
# Builds the distribution as a user's `python -m build` does (sdist, then the wheel from it) with
# a C compiler that links against an old glibc, checks that a registry would render its metadata
# (twine check), tags the wheel py3-none and repairs it to the manylinux tag of that glibc
# (auditwheel), and proves that the repaired wheel installs and runs in a fresh virtual
# environment with no compiler, meson or SUNDIALS on the path: the version agrees everywhere, the
# engine and the FMUs link nothing beyond the manylinux libraries and need no newer glibc, and
# the README's example runs.
#
# Usage: scripts/check-wheel.sh [OUTDIR]   (default dist/). Needs python3 with venv and pip (the
# tools of scripts/wheel-tools.txt go into a virtual environment of the script's own; PYTHON
# chooses the Python) and SUNDIALS' static libraries and headers (Debian: libsundials-dev; other
# places: SUNDIALS_LIBDIR, SUNDIALS_INCLUDEDIR). GLIBC chooses the oldest glibc (default 2.17).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
python=${PYTHON:-python3}
glibc=${GLIBC:-2.17}
sundials_libdir=${SUNDIALS_LIBDIR:-/usr/lib/x86_64-linux-gnu}
sundials_includedir=${SUNDIALS_INCLUDEDIR:-/usr/include}
out=$(mkdir -p "${1:-$root/dist}" && cd "${1:-$root/dist}" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
rm -rf "$out"/*.whl "$out"/*.tar.gz "$out/wheelhouse"
started=$SECONDS
# every tool runs from here: in the source tree its build/ folder would shadow the build package
cd "$work"

echo "== the tools (scripts/wheel-tools.txt) in their own virtual environment"
"$python" -m venv "$work/tools"
"$work/tools/bin/python" -m pip install -q --disable-pip-version-check \
  -r "$root/scripts/wheel-tools.txt" >"$work/tools.log" 2>&1 || { cat "$work/tools.log"; exit 1; }
tool() { PATH="$work/tools/bin:$PATH" "$work/tools/bin/python" -m "$@"; }

# zig's target sees only its own C library headers and libraries: SUNDIALS' are put beside it,
# alone (the system's include and library folders would bring the system's glibc).
mkdir -p "$work/sundials/include" "$work/sundials/lib"
for header in cvode nvector sundials sunlinsol sunmatrix sunnonlinsol; do
  ln -s "$sundials_includedir/$header" "$work/sundials/include/$header"
done
ln -s "$sundials_libdir"/libsundials_*.a "$work/sundials/lib/"
zig="$work/tools/bin/python -m ziglang"

echo "== python -m build (sdist, then the wheel from the sdist), for glibc $glibc"
CC="$zig cc -target x86_64-linux-gnu.$glibc" AR="$zig ar" \
  CFLAGS="-isystem $work/sundials/include" LDFLAGS="-L$work/sundials/lib" \
  nice "$work/tools/bin/python" -m build --outdir "$out" "$root" >"$work/build.log" 2>&1 \
  || { tail -40 "$work/build.log"; exit 1; }
sdist=$(ls "$out"/*.tar.gz)
built=$(ls "$out"/*.whl)
echo "   $(basename "$sdist"), $(basename "$built")"

echo "== wheel tags py3-none (no CPython extension: one wheel for every Python)"
tool wheel tags --python-tag py3 --abi-tag none --remove "$built" >/dev/null
wheel=$(ls "$out"/*.whl)
echo "   $(basename "$wheel")"

echo "== twine check"
tool twine check --strict "$sdist" "$wheel"

echo "== auditwheel repair to manylinux_${glibc/./_}"
tool auditwheel repair --plat "manylinux_${glibc/./_}_x86_64" --wheel-dir "$out/wheelhouse" \
  "$wheel" >"$work/repair.log" 2>&1 || { cat "$work/repair.log"; exit 1; }
repaired=$(ls "$out"/wheelhouse/*.whl)
case "$(basename "$repaired")" in
  *-py3-none-*manylinux_${glibc/./_}_x86_64*) echo "   $(basename "$repaired")" ;;
  *) echo "the repaired wheel is not py3-none manylinux_${glibc/./_}: $repaired" >&2; exit 1 ;;
esac
tool auditwheel show "$repaired" | tr -s ' \n' ' ' | sed 's/^/   /'; echo

echo "== a fresh virtual environment, the repaired wheel and binary dependencies only"
"$python" -m venv "$work/venv"
"$work/venv/bin/python" -m pip install -q --disable-pip-version-check --only-binary=:all: \
  "$repaired" >"$work/pip.log" 2>&1 || { cat "$work/pip.log"; exit 1; }

# From here on only the fresh environment is on the path: no compiler, no meson, no ninja.
fresh() { env -i HOME="$work" PATH="$work/venv/bin" LANG=C.UTF-8 "$@"; }
for program in cc gcc meson ninja; do
  if fresh bash -c "command -v $program" >/dev/null 2>&1; then
    echo "$program is on the fresh environment's path" >&2; exit 1
  fi
done

mkdir "$work/run"
cd "$work/run"
fresh python - "$root/README.md" "$glibc" <<'PYTHON'
import importlib.metadata
import re
import subprocess
import sys
import zipfile
from pathlib import Path

import syssimx
from syssimx import _paths, fmus

installed = importlib.metadata.version("syssimx-engine")
printed = subprocess.run(["syssimx", "--version"], check=True, capture_output=True,
                         text=True).stdout.strip()
assert syssimx.__version__ == installed and printed == f"syssimx {installed}", \
    (syssimx.__version__, installed, printed)
assert "site-packages" in syssimx.__file__, syssimx.__file__
print(f"   syssimx {installed} from {Path(syssimx.__file__).parent}")

# the engine, its FMU host, an exported FMU's binary and every bundled FMU's binaries link no
# SUNDIALS, miss nothing and need no glibc newer than the wheel's tag says (auditwheel does not
# look inside the FMUs)
oldest_glibc = tuple(map(int, sys.argv[2].split(".")))
binaries = [_paths.engine_library(), _paths.fmu_host(), _paths.export_binary()]
for archive in map(Path, map(fmus.path, fmus.available())):
    with zipfile.ZipFile(archive) as fmu:
        for member in fmu.namelist():
            if member.startswith("binaries/") and member.endswith(".so"):
                binaries.append(Path(fmu.extract(member, Path("fmus") / archive.stem)))
for binary in binaries:
    linked = subprocess.run(["/usr/bin/ldd", str(binary)], check=True, capture_output=True,
                            text=True).stdout
    assert "sundials" not in linked and "not found" not in linked, (binary, linked)
    symbols = subprocess.run(["/usr/bin/objdump", "-T", str(binary)], check=True,
                             capture_output=True, text=True).stdout
    needed = {tuple(map(int, version.split("."))) for version in
              re.findall(r"GLIBC_([0-9.]+)\)", symbols)}
    assert max(needed) <= oldest_glibc, (binary, max(needed))
print(f"   {len(binaries)} binaries (engine, FMU host, export binary, FMUs): no SUNDIALS, "
      f"nothing missing, glibc {sys.argv[2]} is enough")

example = re.findall(r"```python\n(.*?)```", Path(sys.argv[1]).read_text(), re.S)[0]
namespace = {}
exec(compile(example, "README.md", "exec"), namespace)
event = namespace["result"].events[0].t
assert abs(event - 0.46507759431173046) < 1e-8, event
assert Path("pendulum.png").stat().st_size > 10_000
print(f"   the README's example ran: event at t = {event:.10f}")
PYTHON
echo "== the wheel is good: $repaired"
echo "   $(du -k "$repaired" | cut -f1) KiB, checked in $((SECONDS - started)) s"
