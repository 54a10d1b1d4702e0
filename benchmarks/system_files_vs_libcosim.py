"""System files read by syssimx and by libcosim (libcosimpy), side by side: the largest
deviation of the same signals, and what libcosim makes of the users' samples.

1. An OSP system structure (tests/python/osp_files.py: the coupled pendulums with variable
   groups, a power bond and a LinearTransformation function): syssimx.osp.read with the Jacobi
   coupling (libcosim's fixed-step algorithm) against CosimExecution.from_osp_config_file.
2. An SSD written here with SSP constructs (a binding that sets an input's start, a
   LinearTransformation; then also a parameter mapped to two targets): syssimx.ssp.read
   against CosimExecution.from_ssp_file, with the closed form (A.y = k 14, B.y = k (2 A.y + 3)).
3. With --samples: OMSimulator's LinearTransformation (an SSD of version 2.0) and libcosim's
   linear_transformation SSD (FMI 1.0), copies with the Open Simulation Platform's step
   annotation, without which libcosim does not run them; libcosim's own crane
   (OspSystemStructure_Bond.xml: variable groups from its OspModelDescription files; a copy
   without the simulators' own step sizes), 10 steps of 1e-4 s; then each SSD and OSP file of
   the samples opened by libcosim in a process of its own (libcosimpy may crash): whether it
   loads.

libcosimpy is installed apart, in a Python of its own:

    python -m venv /tmp/cosim && /tmp/cosim/bin/pip install libcosimpy
    python benchmarks/system_files_vs_libcosim.py --libcosimpy-python /tmp/cosim/bin/python \\
        [--samples ../shared/ssp-samples]
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "python"))
from osp_files import write_osp
from ssp_samples import crane_without_step_sizes
from syssimx import JacobiAlgorithm, fmus
from syssimx.osp import read as read_osp
from syssimx.ssp import read as read_ssp

STEP = 0.01
STEPS = 50

# run by the libcosimpy interpreter: "osp"|"ssp", the path, the signals, the number of steps,
# the JSON file to write (libcosim logs on stdout)
LIBCOSIM_RUN = """
import json, sys
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimObserver import CosimObserver
kind, path = sys.argv[1], sys.argv[2]
execution = (CosimExecution.from_osp_config_file(path) if kind == "osp"
             else CosimExecution.from_ssp_file(path))
observer = CosimObserver.create_last_value()
execution.add_observer(observer)
where = []
for component, variable in json.loads(sys.argv[3]):
    index = execution.slave_index_from_instance_name(component)
    references = {v.name.decode(): v.reference for v in execution.slave_variables(index)}
    where.append((index, references[variable]))
rows = []
for _ in range(int(sys.argv[4])):
    execution.step(1)
    rows.append([observer.last_real_values(i, [r])[0] for i, r in where])
with open(sys.argv[5], "w") as out:
    json.dump(rows, out)
"""

LIBCOSIM_OPEN = """
import sys
from libcosimpy.CosimExecution import CosimExecution
kind, path = sys.argv[1], sys.argv[2]
execution = (CosimExecution.from_osp_config_file(path) if kind == "osp"
             else CosimExecution.from_ssp_file(path))
print("loaded", len(list(execution.slave_infos())), "simulators")
"""

NAMESPACES = ('xmlns:ssd="http://ssp-standard.org/SSP1/SystemStructureDescription" '
              'xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon" '
              'xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues" '
              'xmlns:ssm="http://ssp-standard.org/SSP1/SystemStructureParameterMapping" '
              'xmlns:osp="http://opensimulationplatform.com/SSP/OSPAnnotations"')
CONSTRUCTS = f"""<?xml version="1.0" encoding="UTF-8"?>
<ssd:SystemStructureDescription {NAMESPACES} version="1.0" name="constructs">
  <ssd:System name="constructs">
    <ssd:ParameterBindings>
      <ssd:ParameterBinding>
        <ssd:ParameterValues>
          <ssv:ParameterSet version="1.0" name="shared">
            <ssv:Parameters>
              <ssv:Parameter name="gain"><ssv:Real value="1.5"/></ssv:Parameter>
            </ssv:Parameters>
          </ssv:ParameterSet>
        </ssd:ParameterValues>
        <ssd:ParameterMapping>
          <ssm:ParameterMapping version="1.0">
            <ssm:MappingEntry source="gain" target="A.k"/>
            <ssm:MappingEntry source="gain" target="B.k"/>
          </ssm:ParameterMapping>
        </ssd:ParameterMapping>
      </ssd:ParameterBinding>
    </ssd:ParameterBindings>
    <ssd:Elements>
      <ssd:Component name="A" source="gain.fmu">
        <ssd:Connectors>
          <ssd:Connector name="u" kind="input"><ssc:Real/></ssd:Connector>
          <ssd:Connector name="y" kind="output"><ssc:Real/></ssd:Connector>
        </ssd:Connectors>
        <ssd:ParameterBindings>
          <ssd:ParameterBinding>
            <ssd:ParameterValues>
              <ssv:ParameterSet version="1.0" name="start">
                <ssv:Parameters>
                  <ssv:Parameter name="u"><ssv:Real value="14"/></ssv:Parameter>
                </ssv:Parameters>
              </ssv:ParameterSet>
            </ssd:ParameterValues>
          </ssd:ParameterBinding>
        </ssd:ParameterBindings>
      </ssd:Component>
      <ssd:Component name="B" source="gain.fmu">
        <ssd:Connectors>
          <ssd:Connector name="u" kind="input"><ssc:Real/></ssd:Connector>
          <ssd:Connector name="y" kind="output"><ssc:Real/></ssd:Connector>
        </ssd:Connectors>
      </ssd:Component>
    </ssd:Elements>
    <ssd:Connections>
      <ssd:Connection startElement="A" startConnector="y" endElement="B" endConnector="u">
        <ssc:LinearTransformation factor="2" offset="3"/>
      </ssd:Connection>
    </ssd:Connections>
  </ssd:System>
  <ssd:DefaultExperiment startTime="0">
    <ssd:Annotations>
      <ssc:Annotation type="com.opensimulationplatform">
        <osp:Algorithm>
          <osp:FixedStepAlgorithm baseStepSize="0.01"/>
        </osp:Algorithm>
      </ssc:Annotation>
    </ssd:Annotations>
  </ssd:DefaultExperiment>
</ssd:SystemStructureDescription>
"""


def libcosim(python: str, kind: str, path: Path, signals: list[tuple[str, str]],
             folder: Path, steps: int = STEPS) -> np.ndarray:
    rows = folder / f"libcosim-{kind}.json"
    subprocess.run([python, "-c", LIBCOSIM_RUN, kind, str(path), json.dumps(signals),
                    str(steps), str(rows)], capture_output=True, check=True)
    return np.array(json.loads(rows.read_text()))


def syssimx(imported: object, signals: list[tuple[str, str]], step: float = STEP,
            steps: int = STEPS) -> np.ndarray:
    system = imported.system  # type: ignore[attr-defined]
    system.set_algorithm(JacobiAlgorithm())
    system.initialize(0.0)
    result = system.run(0.0, steps * step, step)
    return np.array([result[c][1][v][1:] for c, v in signals]).T


def compare(title: str, signals: list[tuple[str, str]], ours: np.ndarray,
            theirs: np.ndarray) -> None:
    print(title)
    for column, (component, variable) in enumerate(signals):
        deviation = np.abs(ours[:, column] - theirs[:, column]).max()
        print(f"  {component}.{variable:<7} largest deviation {deviation:.3e} "
              f"(range {np.ptp(ours[:, column]):.3g})")


def with_osp_step(source: Path, folder: Path) -> Path:
    """A copy of the SSD folder `source` whose DefaultExperiment has the OSP step annotation
    (libcosim reads the osp prefix only when the root element declares it)."""
    shutil.copytree(source, folder)
    ssd = folder / "SystemStructure.ssd"
    text = ssd.read_text().replace(
        "<ssd:SystemStructureDescription ",
        '<ssd:SystemStructureDescription '
        'xmlns:osp="http://opensimulationplatform.com/SSP/OSPAnnotations" ', 1)
    annotated = ('<ssd:DefaultExperiment{}><ssd:Annotations><ssc:Annotation '
                 'type="com.opensimulationplatform"><osp:Algorithm>'
                 f'<osp:FixedStepAlgorithm baseStepSize="{STEP}"/></osp:Algorithm>'
                 '</ssc:Annotation></ssd:Annotations></ssd:DefaultExperiment>')
    if "<ssd:DefaultExperiment" in text:
        text = re.sub(r"<ssd:DefaultExperiment( [^>]*)/>",
                      lambda match: annotated.format(match.group(1)), text)
    else:
        text = text.replace("</ssd:SystemStructureDescription>",
                            annotated.format("") + "</ssd:SystemStructureDescription>")
    ssd.write_text(text)
    return folder


def samples(python: str, root: Path) -> None:
    print(f"libcosim on the users' samples ({root}):")
    files = sorted(p for p in root.rglob("*") if p.suffix == ".ssd" or (
        p.suffix == ".xml" and p.name.startswith("OspSystemStructure")))
    for path in files:
        kind = "ssp" if path.suffix == ".ssd" else "osp"
        target = path.parent if kind == "ssp" else path
        done = subprocess.run([python, "-c", LIBCOSIM_OPEN, kind, str(target)],
                              capture_output=True, text=True, timeout=120)
        loaded = [line for line in done.stdout.splitlines() if line.startswith("loaded")]
        outcome = loaded[0] if loaded and done.returncode == 0 else \
            f"crashed (signal {-done.returncode})" if done.returncode < 0 else \
            "refused: " + (done.stderr.strip().splitlines() or ["(no message)"])[-1][:100]
        print(f"  {path.relative_to(root)}: {outcome}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--libcosimpy-python", default=os.environ.get("LIBCOSIMPY_PYTHON"),
                        required="LIBCOSIMPY_PYTHON" not in os.environ,
                        help="a Python interpreter with libcosimpy installed")
    parser.add_argument("--samples", type=Path, default=None,
                        help="the users' samples folder (ssp-samples) to open with libcosim")
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        signals = [("P1", "theta"), ("P2", "theta"), ("Spring", "tau2")]
        osp = write_osp(folder / "osp")
        compare(f"OSP coupled pendulums, {STEPS} steps of {STEP} s, Jacobi vs fixed-step:",
                signals, syssimx(read_osp(osp), signals),
                libcosim(args.libcosimpy_python, "osp", osp.parent, signals, folder))
        signals = [("A", "y"), ("B", "y")]
        without_mapping = re.sub(r"<ssd:ParameterMapping>.*?</ssd:ParameterMapping>", "",
                                 CONSTRUCTS, flags=re.DOTALL)
        for title, text, k in (("an input's start and a transformation", without_mapping, 1.0),
                               ("the same and a mapping of gain = 1.5 to A.k and B.k",
                                CONSTRUCTS, 1.5)):
            ssd = folder / "ssp" / "SystemStructure.ssd"
            ssd.parent.mkdir(exist_ok=True)
            ssd.write_text(text)
            shutil.copy(fmus.path("gain"), ssd.parent / "gain.fmu")
            ours = syssimx(read_ssp(ssd), signals)
            theirs = libcosim(args.libcosimpy_python, "ssp", ssd.parent, signals, folder)
            compare(f"SSD with {title}:", signals, ours, theirs)
            print(f"  last A.y, B.y: closed form {k * 14:g}, {k * (2 * k * 14 + 3):g}; syssimx "
                  f"{ours[-1, 0]:g}, {ours[-1, 1]:g}; libcosim {theirs[-1, 0]:g}, "
                  f"{theirs[-1, 1]:g}")
        if args.samples is not None:
            omsimulator = with_osp_step(args.samples.resolve() / "omsimulator" /
                                        "LinearTransformation", folder / "oms")
            signals = [("Gain1", "y"), ("Add1", "y")]
            compare("OMSimulator's LinearTransformation (SSP 2.0), 50 steps of 0.01 s:",
                    signals, syssimx(read_ssp(omsimulator / "SystemStructure.ssd"), signals),
                    libcosim(args.libcosimpy_python, "ssp", omsimulator, signals, folder))
            # libcosim's own SSD: the FMI 1.0 identity.fmu, two .ssv files, a transformation
            shutil.copytree(args.samples / "libcosim" / "fmi1", folder / "libcosim" / "fmi1")
            identity = with_osp_step(args.samples / "libcosim" / "ssp" / "linear_transformation",
                                     folder / "libcosim" / "ssp" / "linear_transformation")
            signals = [("identity1", "realOut"), ("identity2", "realOut")]
            compare("libcosim's linear_transformation SSD (FMI 1.0), 50 steps of 0.01 s "
                    "(libcosim binds the first .ssv, syssimx the later, as the standard says):",
                    signals, syssimx(read_ssp(identity / "SystemStructure.ssd"), signals),
                    libcosim(args.libcosimpy_python, "ssp", identity, signals, folder))
            crane = crane_without_step_sizes(args.samples.resolve(), folder / "crane")
            signals = [("CraneController", f"p_Crane.e[{i}]") for i in (1, 2, 3)] + \
                [("KnuckleBoomCrane", f"p_Crane.f[{i}]") for i in (1, 2, 3)]
            compare("libcosim's crane (variable groups), 10 steps of 1e-4 s:", signals,
                    syssimx(read_osp(crane), signals, 1e-4, 10),
                    libcosim(args.libcosimpy_python, "osp", crane, signals, folder, 10))
    if args.samples is not None:
        samples(args.libcosimpy_python, args.samples)


if __name__ == "__main__":
    main()
