#!/usr/bin/env bash
# Installs and builds syssimx, then runs the main job: the hybrid pendulum co-simulation of the
# seed tutorial with the Euler and CVODE FMUs. Prints the located event times, writes a plot.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/install.sh"
mkdir -p "$root/out"
cd "$root/out"
"$root/.venv/bin/python" "$root/examples/hybrid_pendulum.py" --plot "$root/out/hybrid_pendulum.png"
