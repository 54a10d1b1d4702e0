"""Components of one FMU file share its extraction (one mapped binary), unless the FMU may be
instantiated only once per process; the last user removes the directory."""

from __future__ import annotations

import gc
import zipfile
from pathlib import Path

from syssimx import FMUComponent, System, fmus


def once_per_process_copy(tmp_path: Path) -> Path:
    """pendulum_euler.fmu declaring canBeInstantiatedOnlyOncePerProcess."""
    source = Path(fmus.path("pendulum_euler"))
    target = tmp_path / "pendulum_once.fmu"
    with zipfile.ZipFile(source) as src, zipfile.ZipFile(target, "w") as dst:
        for item in src.infolist():
            data = src.read(item)
            if item.filename == "modelDescription.xml":
                data = data.replace(b"<CoSimulation ",
                                    b'<CoSimulation canBeInstantiatedOnlyOncePerProcess="true" ')
            dst.writestr(item, data)
    return target


def test_components_of_one_file_share_one_extraction() -> None:
    # components of earlier tests that wait in reference cycles would still hold the extraction
    gc.collect()
    first = FMUComponent("A", fmus.path("pendulum_euler"))
    second = FMUComponent("B", fmus.path("pendulum_euler"))
    other = FMUComponent("C", fmus.path("pendulum_cvode"))
    directory = first._unzip_dir
    assert second._unzip_dir == directory
    assert other._unzip_dir != directory
    first.free()
    assert directory.is_dir()  # B still uses it
    second.free()
    assert not directory.exists()
    other.free()


def run_pendulums(starts: dict[str, float]) -> dict[str, list[float]]:
    system = System("pendulums")
    for name, theta0 in starts.items():
        pendulum = FMUComponent(name, fmus.path("pendulum_euler"))
        pendulum.set_parameters(theta0=theta0)
        system.add_component(pendulum)
    system.initialize(0.0)
    result = system.run(0.0, 0.5, 0.05)
    return {name: list(result[name][1]["theta"]) for name in starts}


def test_shared_binary_keeps_instances_independent() -> None:
    together = run_pendulums({"A": 0.5, "B": -0.2})
    assert together["A"] == run_pendulums({"A": 0.5})["A"]
    assert together["B"] == run_pendulums({"B": -0.2})["B"]


def test_once_per_process_fmu_gets_a_private_extraction(tmp_path: Path) -> None:
    archive = once_per_process_copy(tmp_path)
    first = FMUComponent("A", archive)
    second = FMUComponent("B", archive)
    assert first._unzip_dir != second._unzip_dir
    directories = (first._unzip_dir, second._unzip_dir)
    first.free()
    second.free()
    assert not any(d.exists() for d in directories)


def test_a_forked_child_neither_removes_nor_reuses_its_parent_s_folder() -> None:
    """An ensemble's workers are forked: before, a worker that dropped a component it
    inherited removed the folder its parent still used."""
    import os

    gc.collect()
    inherited = FMUComponent("A", fmus.path("pendulum_euler"))
    folder = inherited._unzip_dir
    read, write = os.pipe()
    child = os.fork()
    if child == 0:  # drop the inherited component, extract and drop one of its own
        status = 1
        try:
            inherited = None
            gc.collect()
            own = FMUComponent("B", fmus.path("pendulum_euler"))
            os.write(write, str(own._unzip_dir).encode())
            own = None
            gc.collect()
            status = 0
        finally:
            os._exit(status)
    os.close(write)
    with os.fdopen(read) as pipe:
        childs_folder = Path(pipe.read())
    _, status = os.waitpid(child, 0)
    assert os.waitstatus_to_exitcode(status) == 0
    assert folder.is_dir() and childs_folder != folder
    assert not childs_folder.exists()  # the child removed its own
    assert inherited._unzip_dir == folder
