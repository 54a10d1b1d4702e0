"""Loading an FMU whose modelDescription.xml has 10**6 variables (large Dymola exports exist).

Builds gain.fmu's binary with a generated description of N variables (the three of gain.fmu,
then locals, every 10th a parameter and every 100th an output, with units, starts and
descriptions), then loads it side by side, each in a fresh process:

- fmpy:     fmpy.read_model_description(path, validate=False), what syssimx called before;
- read_fmu: syssimx's reader (the engine's ssx_md_read into arrays) plus ports, parameters,
  units and feedthrough;
- FMUComponent: the whole construction (archive checks, reading, extraction, loading the
  binary; no instance);
- import: `import syssimx` alone, the part of the two above that is not reading.

Each includes its imports. Prints wall time, CPU time (user + system, steadier than wall time
on a busy machine) and peak resident memory (getrusage of the child), and the ratios to fmpy.

    python benchmarks/large_model_description.py [N]      (default 1000000)
"""

from __future__ import annotations

import json
import resource
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

from syssimx import fmus

UNITS = ("m", "s", "K", "Pa", "kg", "-", "rad/s")

CHILD = """
import json, resource, sys, time
start, cpu_start = time.perf_counter(), time.process_time()
kind, path = sys.argv[1], sys.argv[2]
if kind == "import":
    import syssimx
    count = None
elif kind == "fmpy":
    from fmpy import read_model_description
    description = read_model_description(path, validate=False)
    count = len(description.modelVariables)
elif kind == "read_fmu":
    from syssimx.fmu.info import read_fmu
    count = len(read_fmu(path).variables)
else:
    from syssimx import FMUComponent
    count = len(FMUComponent("big", path).info.variables)
seconds, cpu = time.perf_counter() - start, time.process_time() - cpu_start
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
print(json.dumps({"seconds": seconds, "cpu": cpu, "peak_bytes": peak, "variables": count}))
"""


def variable_lines(first: int, last: int) -> list[str]:
    lines = []
    for i in range(first, last):
        if i % 10 == 0:
            head = 'causality="parameter" variability="fixed" initial="exact"'
            value = f'<Real unit="{UNITS[i % len(UNITS)]}" start="{i * 1e-3!r}"/>'
        elif i % 100 == 1:
            head = 'causality="output" variability="continuous" initial="calculated"'
            value = f'<Real unit="{UNITS[i % len(UNITS)]}"/>'
        else:
            head = 'causality="local" variability="continuous" initial="calculated"'
            value = f'<Real unit="{UNITS[i % len(UNITS)]}"/>'
        lines.append(f'    <ScalarVariable name="block{i // 1000}.part{i % 1000}.x" '
                     f'valueReference="{i}" {head} description="variable number {i}">\n'
                     f'      {value}\n    </ScalarVariable>\n')
    return lines


def build(count: int, folder: Path) -> Path:
    """gain.fmu with `count` variables (its own three first, so its binary still fits)."""
    with zipfile.ZipFile(fmus.path("gain")) as gain:
        text = gain.read("modelDescription.xml").decode()
        binary = gain.read("binaries/linux64/gain.so")
    head, rest = text.split("  <ModelVariables>\n")
    gain_variables, tail = rest.split("  </ModelVariables>\n")
    outputs = "".join(f'      <Unknown index="{i + 1}" dependencies="2"/>\n'
                      for i in range(3, count) if i % 100 == 1 and i % 10 != 0)
    tail = tail.replace("    </Outputs>\n", outputs + "    </Outputs>\n")
    path = folder / "large.fmu"
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        with archive.open("modelDescription.xml", "w", force_zip64=True) as stream:
            stream.write(head.encode() + b"  <ModelVariables>\n" + gain_variables.encode())
            # in batches: a child's peak memory counts its parent's at the fork
            for first in range(3, count, 10_000):
                batch = variable_lines(first, min(first + 10_000, count))
                stream.write("".join(batch).encode())
            stream.write(b"  </ModelVariables>\n" + tail.encode())
        archive.writestr("binaries/linux64/gain.so", binary)
    return path


def measure(kind: str, path: Path) -> dict[str, float]:
    done = subprocess.run([sys.executable, "-c", CHILD, kind, str(path)], capture_output=True,
                          text=True, check=True)
    return json.loads(done.stdout)


def main() -> None:
    count = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
    with tempfile.TemporaryDirectory() as folder:
        path = build(count, Path(folder))
        with zipfile.ZipFile(path) as archive:
            size = archive.getinfo("modelDescription.xml").file_size
        print(f"modelDescription.xml: {count} variables, {size / 2**20:.0f} MiB")
        parent = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**10
        print(f"(this process's peak, {parent:.0f} MiB, is the floor of every child's: Linux "
              "counts it at the fork)")
        kinds = ("fmpy", "read_fmu", "FMUComponent", "import")
        results = {kind: measure(kind, path) for kind in kinds}
    base = results["fmpy"]
    print(f"{'reader':<14} {'time':>8} {'CPU':>8} {'peak RSS':>10} {'time ratio':>11} "
          f"{'CPU ratio':>10} {'memory ratio':>13}")
    for kind, result in results.items():
        assert result["variables"] in (count, None), (kind, result)
        print(f"{kind:<14} {result['seconds']:>7.2f}s {result['cpu']:>7.2f}s "
              f"{result['peak_bytes'] / 2**20:>7.0f} MiB "
              f"{base['seconds'] / result['seconds']:>10.1f}x "
              f"{base['cpu'] / result['cpu']:>9.1f}x "
              f"{base['peak_bytes'] / result['peak_bytes']:>12.1f}x")


if __name__ == "__main__":
    main()
