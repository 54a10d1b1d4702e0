"""Observers and streamed runs: what a Python observer costs per sample, and a run streamed to
Parquet in bounded memory, as ratios and figures from one run.

One Gain FMU (y = k*u, one output), no events, dt 1e-3: the cheapest step the engine takes,
so what recording costs is not hidden behind the model.

  per sample   best of --repeat runs of --steps steps, side by side in this process: the
               history alone; with a Python observer that does nothing (System.add_observer:
               one cffi call and one numpy array per sample); streamed to Parquet
               (run(stream_to=...), the engine hands pyarrow blocks of about 8 MB)
  bounded      one child process per size, each a fresh interpreter: a run of N samples
               streamed to Parquet with keep_history=False, its wall time per sample, the peak
               resident size during the run above the size before it (Linux: the peak is reset
               through /proc/self/clear_refs, read as VmHWM) and its file; and, for contrast,
               the same run keeping the history in memory without a file, for the sizes up to
               --in-memory-max

    python benchmarks/streaming.py [--steps N] [--repeat N] [--sizes N ...]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from syssimx import FMUComponent, System, fmus

DT = 1e-3


def gain_system() -> System:
    system = System("gain")
    system.add_component(FMUComponent("G", fmus.path("gain")))
    system.initialize(0.0)
    return system


class Idle:
    """An observer that keeps nothing: its cost is the call itself."""

    def step_complete(self, t: float, micro: int, values: object) -> None:
        pass


def timed_run(steps: int, mode: str, folder: Path) -> float:
    """Seconds per sample of one run of `steps` steps recorded the way `mode` says."""
    system = gain_system()
    stream = folder / "run.parquet" if mode == "parquet" else None
    if mode == "observer":
        system.add_observer(Idle())
    start = time.perf_counter()
    system.run(0.0, steps * DT, DT, stream_to=stream)
    return (time.perf_counter() - start) / steps


def resident_kb(field: str) -> int:
    """A line of /proc/self/status in kB (VmRSS: now, VmHWM: the peak since the last reset)."""
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith(field + ":"):
            return int(line.split()[1])
    raise RuntimeError(f"no {field} in /proc/self/status")


def child(samples: int, streamed: bool, folder: Path) -> dict[str, float]:
    """One run in this (fresh) process; its figures as a dict."""
    system = gain_system()
    path = folder / f"run{samples}.parquet"
    if streamed:
        import pyarrow.parquet  # noqa: F401  (imported before the baseline, not counted)
    Path("/proc/self/clear_refs").write_text("5")  # the peak starts again from now
    before_kb = resident_kb("VmRSS")
    start = time.perf_counter()
    if streamed:
        system.run(0.0, samples * DT, DT, stream_to=path, keep_history=False)
    else:
        system.run(0.0, samples * DT, DT)
    wall = time.perf_counter() - start
    growth_kb = resident_kb("VmHWM") - before_kb
    size = path.stat().st_size if streamed else 0
    return {"wall": wall, "peak_mb": growth_kb / 1024, "file_mb": size / 1e6,
            "history_mb": system.history_bytes() / 1e6}


def in_child(samples: int, streamed: bool, folder: Path) -> dict[str, float]:
    out = subprocess.run([sys.executable, __file__, "--child", str(samples),
                          "--streamed" if streamed else "--in-memory", "--folder", str(folder)],
                         check=True, capture_output=True, text=True)
    return json.loads(out.stdout.splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=200_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--sizes", type=int, nargs="+",
                        default=[1_000_000, 10_000_000, 100_000_000])
    parser.add_argument("--in-memory-max", type=int, default=10_000_000)
    parser.add_argument("--child", type=int, help=argparse.SUPPRESS)
    parser.add_argument("--streamed", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--in-memory", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--folder", type=Path, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child is not None:
        print(json.dumps(child(args.child, args.streamed, args.folder)))
        return

    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        modes = ("history", "observer", "parquet")
        best = {mode: float("inf") for mode in modes}
        for _ in range(args.repeat):
            for mode in modes:  # interleaved: a drift of the machine hits every mode
                best[mode] = min(best[mode], timed_run(args.steps, mode, folder))
        print(f"one Gain FMU, {args.steps} steps of {DT} s: seconds per sample (best of "
              f"{args.repeat})")
        print(f"{'recording':>28} {'us/sample':>10} {'ratio':>7} {'added us/sample':>16}")
        labels = {"history": "history only", "observer": "+ Python observer (no-op)",
                  "parquet": "+ streamed to Parquet"}
        for mode in modes:
            print(f"{labels[mode]:>28} {best[mode] * 1e6:>10.3f} "
                  f"{best[mode] / best['history']:>7.2f} "
                  f"{(best[mode] - best['history']) * 1e6:>16.3f}")

        print()
        print("one run per fresh process: streamed to Parquet without history, against the "
              "history in memory")
        print(f"{'samples':>12} {'how':>22} {'ns/sample':>10} {'peak growth MB':>15} "
              f"{'history MB':>11} {'file MB':>8}")
        for samples in args.sizes:
            runs = [("streamed, no history", True)]
            if samples <= args.in_memory_max:
                runs.append(("history in memory", False))
            for label, streamed in runs:
                r = in_child(samples, streamed, folder)
                print(f"{samples:>12} {label:>22} {r['wall'] / samples * 1e9:>10.1f} "
                      f"{r['peak_mb']:>15.1f} {r['history_mb']:>11.1f} {r['file_mb']:>8.1f}")
                (folder / f"run{samples}.parquet").unlink(missing_ok=True)


if __name__ == "__main__":
    main()
