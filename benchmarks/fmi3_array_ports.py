"""Opening an FMI 3.0 FMU with one large array input: what an array of N elements costs.

Builds gain_fmi3.fmu's binary with its description plus a Float64 input array `a` of N
elements (each with a start value) and opens it with FMUComponent (reading, ports,
extraction, loading the binary; no instance), each N in a fresh process. Prints, per N, the
wall and CPU time of the construction alone (`import syssimx` done before), the Python memory
it allocated and still holds (tracemalloc, a second process), and the growth of the peak
resident memory; N = 0, the FMU without the array, comes first, and the last column is the
CPU time's ratio to it (CPU time: the machines are shared, wall times vary with their load).

    python benchmarks/fmi3_array_ports.py [N ...]      (default 1000 10000 100000 1000000)
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

from syssimx import fmus

CHILD = """
import json, resource, sys, time, tracemalloc
traced = sys.argv[2] == "traced"
from syssimx import FMUComponent
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
if traced:
    tracemalloc.start()
start, cpu_start = time.perf_counter(), time.process_time()
component = FMUComponent("big", sys.argv[1])
seconds, cpu = time.perf_counter() - start, time.process_time() - cpu_start
held = tracemalloc.get_traced_memory()[0] if traced else 0
grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024 - before
print(json.dumps({"seconds": seconds, "cpu": cpu, "held": held, "grown": grown,
                  "inputs": len(component.inputs)}))
"""

ARRAY = ('    <Float64 name="a" valueReference="4" causality="input" variability="continuous" '
         'start="{starts}">\n      <Dimension start="{count}"/>\n    </Float64>\n')


def build(count: int, folder: Path) -> Path:
    """gain_fmi3.fmu with an input array of `count` elements (none for 0)."""
    with zipfile.ZipFile(fmus.path("gain_fmi3")) as gain:
        entries = {name: gain.read(name) for name in gain.namelist()}
    text = entries["modelDescription.xml"].decode()
    if count:
        starts = " ".join(str(i % 7 * 0.5) for i in range(count))
        text = text.replace("  </ModelVariables>",
                            ARRAY.format(starts=starts, count=count) + "  </ModelVariables>")
    path = folder / f"array_{count}.fmu"
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in {**entries, "modelDescription.xml": text.encode()}.items():
            archive.writestr(name, data)
    return path


def measure(path: Path, mode: str) -> dict[str, float]:
    done = subprocess.run([sys.executable, "-c", CHILD, str(path), mode], capture_output=True,
                          text=True, check=True)
    return json.loads(done.stdout)


def main() -> None:
    counts = [int(n) for n in sys.argv[1:]] or [1_000, 10_000, 100_000, 1_000_000]
    print(f"{'elements':>9} {'time':>8} {'CPU':>8} {'Python memory':>14} {'peak RSS growth':>16}"
          f" {'CPU / N=0':>10}")
    base: dict[str, float] | None = None
    with tempfile.TemporaryDirectory() as folder:
        for count in [0, *counts]:
            path = build(count, Path(folder))
            result = measure(path, "plain")
            result["held"] = measure(path, "traced")["held"]
            assert result["inputs"] == count + 1, result
            base = base or result
            print(f"{count:>9} {result['seconds']:>7.3f}s {result['cpu']:>7.3f}s "
                  f"{result['held'] / 2**20:>10.1f} MiB {result['grown'] / 2**20:>12.1f} MiB "
                  f"{result['cpu'] / base['cpu']:>9.1f}x")
            path.unlink()


if __name__ == "__main__":
    main()
