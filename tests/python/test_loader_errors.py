"""Every bad entry of a system description is a ConfigError naming the file, the entry (with
its YAML line) and what is wrong; nothing runs."""

from __future__ import annotations

from pathlib import Path

import pytest
from syssimx import ConfigurationError
from syssimx.system.loader import ConfigError, build_system, run_from_config

BASE = """\
system: {name: s}
components:
  - name: Src
    class: "quickstart:LinearSource"
  - name: Int
    class: "quickstart:Integrator"
connections:
  - {src: Src.y, dst: Int.u}
run: {t0: 0, tf: 1, dt: 0.1}
"""
PENDULUM = "components:\n  - name: P\n    fmu: pendulum_euler\n"
PENDULUM_PARAMETERS = "['L', 'euler_step_size', 'g', 'inertia', 'm', 'omega0', 'theta0']"

# description -> the message after "<file>"
BUILD_ERRORS = {
    BASE + "conections: []\n":
        ", line 1: top level: unknown key(s) ['conections']; known: ['system', 'components', "
        "'connections', 'event_connections', 'clock_connections', 'algorithm', 'run']",
    "system: {name: s}\ncomponents: []\n":
        ", line 1: components: a system needs a non-empty list of components",
    BASE.replace("system: {name: s}", "system: {title: s}"):
        ", line 1: system: must be a mapping {name: ..., undeclared_dependencies: "
        "all or none}, got {'title': 's'}",
    BASE.replace("system: {name: s}", "system: {name: 3}"):
        ", line 1: system.name: must be a non-empty string, got 3",
    "components:\n  - Src\n":
        ": components[0]: must be a mapping with 'name' and 'class' (or 'fmu'), got string "
        "'Src'",
    "components:\n  - class: 'quickstart:LinearSource'\n":
        ", line 2: components[0]: needs a 'name' (a non-empty string)",
    "components:\n  - name: A\n    class: 'quickstart:LinearSource'\n    parameter: {}\n":
        ", line 2: components[0] 'A': unknown key(s) ['parameter']; known: ['name', 'class', "
        "'fmu', 'interface', 'args', 'parameters', 'inputs', 'dependencies', "
        "'event_indicators', 'event_handlers']",
    "components:\n  - name: A\n":
        ", line 2: components[0] 'A': needs 'class' (\"module:Class\") or 'fmu' (a bundled "
        "FMU name or a path to an .fmu file)",
    "components:\n  - name: A\n    class: quickstart.LinearSource\n":
        ", line 2: components[0] 'A': class 'quickstart.LinearSource' is not of the form "
        "'module.path:ClassName'",
    "components:\n  - name: A\n    class: 'no_such_module_here:Thing'\n":
        ", line 2: components[0] 'A': module 'no_such_module_here' is not allowed: a system file "
        "may name classes of syssimx and of modules you allow (importing a module runs its "
        "code); allow it with --allow-module no_such_module_here or "
        "allowed_modules=['no_such_module_here']",
    "components:\n  - name: A\n    class: 'quickstart:Nothing'\n":
        ", line 2: components[0] 'A': module 'quickstart' has no 'Nothing'",
    "components:\n  - name: A\n    class: 'pathlib:Path'\n":
        ", line 2: components[0] 'A': module 'pathlib' is not allowed: a system file may name "
        "classes of syssimx and of modules you allow (importing a module runs its code); allow "
        "it with --allow-module pathlib or allowed_modules=['pathlib']",
    "components:\n  - name: A\n    class: 'quickstart:System'\n":
        ", line 2: components[0] 'A': quickstart:System is not a CoSimComponent",
    "components:\n  - name: A\n    class: 'quickstart:LinearSource'\n    args: {c: 1}\n":
        ", line 2: components[0] 'A': cannot construct quickstart:LinearSource with args "
        "{'c': 1}: LinearSource.__init__() got an unexpected keyword argument 'c'",
    "components:\n  - name: A\n    class: 'quickstart:LinearSource'\n    args: [1]\n":
        ", line 2: components[0] 'A': 'args' must be a mapping, got list [1]",
    PENDULUM + "    parameters: {theta9: 1}\n":
        ", line 2: components[0] 'P' parameters: component 'P' has no parameter 'theta9' "
        "(did you mean 'theta0'?); "
        f"known parameters: {PENDULUM_PARAMETERS}",
    PENDULUM + "    parameters: {theta0: abc}\n":
        ", line 2: components[0] 'P' parameters: P.theta0 is Real; got str 'abc'",
    "components:\n  - {name: PI, fmu: pi_controller, inputs: {setpont: 1}}\n":
        ", line 2: components[0] 'PI' inputs: component 'PI' has no input 'setpont'; inputs: "
        "['measurement', 'setpoint']",
    "components:\n  - {name: PI, fmu: pi_controller, inputs: {kp: 1}}\n":
        ", line 2: components[0] 'PI' inputs: component 'PI' has no input 'kp' (a parameter: "
        "give it under 'parameters'); inputs: ['measurement', 'setpoint']",
    "components:\n  - {name: PI, fmu: pi_controller, inputs: {setpoint: one}}\n":
        ", line 2: components[0] 'PI' inputs: port 'setpoint' is REAL; got str",
    "components:\n  - {name: PI, fmu: pi_controller, inputs: [setpoint]}\n":
        ", line 2: components[0] 'PI': 'inputs' must be a mapping, got list ['setpoint']",
    PENDULUM + "    class: 'syssimx:FMUComponent'\n":
        ", line 2: components[0] 'P': give either 'class' or 'fmu', not both",
    "components:\n  - {name: A, class: 'quickstart:LinearSource'}\n"
    "  - {name: A, class: 'quickstart:Integrator'}\n":
        ", line 3: components[1] 'A': System: a component named 'A' already exists",
    PENDULUM + "    event_indicators: [{name: hit, variable: thetta, direction: -1}]\n":
        ", line 4: components[0] 'P' event_indicators[0]: P.hit: variable 'thetta' is not an "
        "output; outputs: ['theta', 'omega', 'alpha']",
    PENDULUM + "    event_indicators: [{name: hit, variable: theta, direction: 2}]\n":
        ", line 4: components[0] 'P' event_indicators[0]: P.hit: direction must be -1, 0 or +1",
    PENDULUM + "    event_indicators: [{name: hit, var: theta}]\n":
        ", line 4: components[0] 'P' event_indicators[0]: unknown key(s) ['var']",
    PENDULUM + "    event_handlers: [{input: bounce, reinitialize: {omega9: -omega}}]\n":
        ", line 4: components[0] 'P' event_handlers[0]: reinitialize: 'P' has no parameter "
        f"'omega9'; parameters: {PENDULUM_PARAMETERS}",
    PENDULUM + "    event_handlers: [{input: bounce, reinitialize: {omega0: -omegga}}]\n":
        ", line 4: components[0] 'P' event_handlers[0]: omega0: 'omegga' is not an output of "
        "'P'; outputs: ['alpha', 'omega', 'theta']",
    PENDULUM + "    event_handlers: [{input: bounce, reinitialize: {omega0: 'omega + 1'}}]\n":
        ", line 4: components[0] 'P' event_handlers[0]: omega0: 'omega + 1' is not 'output', "
        "'-output' or 'number*output'",
    PENDULUM + "    event_handlers: [{input: bounce}]\n":
        ", line 4: components[0] 'P' event_handlers[0]: needs both ['input', 'reinitialize']",
    BASE.replace("Src.y, dst: Int.u", "Src.z, dst: Int.u"):
        ", line 8: connections[0]: Src.z -> Int.u: 'Src' has no output 'z'; outputs: ['y']",
    BASE.replace("Src.y, dst: Int.u", "Source.y, dst: Int.u"):
        ", line 8: connections[0]: s: unknown component 'Source' (did you mean "
        "'Src'?); components: ['Int', 'Src']",
    BASE.replace("{src: Src.y, dst: Int.u}", "{src: Srcy, dst: Int.u}"):
        ", line 8: connections[0]: src 'Srcy' is neither 'Component.port' nor {component: ..., "
        "port: ...}",
    BASE.replace("{src: Src.y, dst: Int.u}", "{from: Src.y, dst: Int.u}"):
        ", line 8: connections[0]: must be a mapping {src, dst}, got {'from': 'Src.y', "
        "'dst': 'Int.u'}",
    BASE.replace("  - {src: Src.y, dst: Int.u}", "  - {src: Src.y, dst: Int.u}\n"
                 "  - {src: Int.y, dst: Int.u}"):
        ", line 9: connections[1]: Int.y -> Int.u: input Int.u is already driven by Src.y",
    BASE.replace("connections:\n  - {src: Src.y, dst: Int.u}", "connections: {src: Src.y}"):
        ", line 1: connections: must be a list, got mapping",
    BASE + "event_connections:\n  - {src: Src.hit, dst: Int.reset}\n":
        ", line 11: event_connections[0]: Src.hit -> Int.reset: 'Src' has no event indicator "
        "'hit'; indicators: none",
    BASE + "algorithm: {type: newton}\n":
        ", line 10: algorithm: unknown type 'newton'; types: ['gauss_seidel', 'hybrid', "
        "'ijcsa', 'jacobi']",
    BASE + "algorithm: {type: hybrid, tol_tim: 1.0e-9}\n":
        ", line 10: algorithm: invalid options for 'hybrid': HybridAlgorithm.__init__() got an "
        "unexpected keyword argument 'tol_tim'",
    BASE + "algorithm: {type: jacobi, tolerance: -1}\n":
        ", line 10: algorithm: invalid options for 'jacobi': Jacobi: tolerance > 0, max_iter "
        ">= 1 and 0 < damping <= 1 are required (got -1, 100, 1.0)",
    BASE + "algorithm: {type: hybrid, max_deferrals: -1}\n":
        ", line 10: algorithm: invalid options for 'hybrid': HybridAlgorithm: max_deferrals "
        "must be an integer >= 0, got -1",
    BASE + "algorithm: {type: hybrid, coupling: {type: hybrid}}\n":
        ", line 10: algorithm.coupling: the coupling of a hybrid algorithm is jacobi, "
        "gauss_seidel or ijcsa",
    BASE + "algorithm: {type: jacobi\n":
        ", line 11: not valid YAML: expected ',' or '}', but got '<stream end>'",
}

RUN_ERRORS = {
    BASE.replace("run: {t0: 0, tf: 1, dt: 0.1}", "run: {t0: 0, tf: 1}"):
        ", line 9: run: missing ['dt']: add them to the description's 'run' entry or pass "
        "them as arguments",
    BASE.replace("run: {t0: 0, tf: 1, dt: 0.1}", "run: {t0: 0, tf: one, dt: 0.1}"):
        ", line 9: run.tf: must be a finite number, got 'one'",
    BASE.replace("run: {t0: 0, tf: 1, dt: 0.1}", "run: {t0: 0, tf: 1, dt: 0.1, t1: 3}"):
        ", line 9: run: unknown key(s) ['t1']; known: ['t0', 'tf', 'dt']",
}


def write(tmp_path: Path, text: str, name: str = "system.yaml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


@pytest.mark.parametrize(("text", "message"), BUILD_ERRORS.items(),
                         ids=[f"build-{i}" for i in range(len(BUILD_ERRORS))])
def test_a_bad_entry_is_named_with_its_file_and_line(tmp_path: Path, text: str, message: str):
    path = write(tmp_path, text)
    with pytest.raises(ConfigError) as caught:
        build_system(path, allowed_modules=["quickstart"])
    assert str(caught.value) == f"{path}{message}"


@pytest.mark.parametrize(("text", "message"), RUN_ERRORS.items(),
                         ids=[f"run-{i}" for i in range(len(RUN_ERRORS))])
def test_a_bad_run_entry_is_named(tmp_path: Path, text: str, message: str):
    path = write(tmp_path, text)
    with pytest.raises(ConfigError) as caught:
        run_from_config(path, allowed_modules=["quickstart"])
    assert str(caught.value) == f"{path}{message}"


def test_unknown_bundled_fmu_suggests_the_close_ones(tmp_path: Path):
    path = write(tmp_path, "components:\n  - name: P\n    fmu: pendulum_cvod\n")
    with pytest.raises(ConfigError, match=r", line 2: components\[0\] 'P': no bundled FMU "
                       r"named 'pendulum_cvod' \(did you mean 'pendulum_cvode'"):
        build_system(path)


def test_a_relative_fmu_path_is_read_beside_the_description(tmp_path: Path):
    path = write(tmp_path, "components:\n  - name: P\n    fmu: models/missing.fmu\n")
    with pytest.raises(ConfigError) as caught:
        build_system(path)
    assert f"{tmp_path / 'models' / 'missing.fmu'}" in str(caught.value)
    assert str(caught.value).startswith(f"{path}, line 2: components[0] 'P': cannot construct "
                                        "syssimx:FMUComponent with args")


def test_json_errors_name_the_line(tmp_path: Path):
    path = write(tmp_path, '{"components": [\n}', "system.json")
    with pytest.raises(ConfigError) as caught:
        build_system(path)
    assert str(caught.value) == f"{path}, line 2: not valid JSON: Expecting value"


def test_a_missing_file_and_a_mapping_without_file(tmp_path: Path):
    with pytest.raises(ConfigError, match=r"none\.yaml: cannot read the system description: "
                       r"\[Errno 2\] No such file or directory"):
        build_system(tmp_path / "none.yaml")
    with pytest.raises(ConfigError) as caught:
        build_system({"components": [{"name": "A"}]})
    assert str(caught.value) == ("components[0] 'A': needs 'class' (\"module:Class\") or 'fmu' "
                                 "(a bundled FMU name or a path to an .fmu file)")
    # ConfigError is SysSimX's ValueError and syssimx's ConfigurationError
    assert issubclass(ConfigError, ValueError) and issubclass(ConfigError, ConfigurationError)
