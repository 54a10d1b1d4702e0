"""The ``syssimx`` command line: inspect an FMU, list the bundled FMUs, simulate one FMU, run
or describe a system description (YAML or JSON) or an SSP (.ssp archive or .ssd file), sweep
a system over parameters.

    syssimx info pendulum_cvode
    syssimx fmus
    syssimx simulate pendulum_euler --stop-time 1 --step-size 0.05 --set theta0=0.5 \\
        --event theta:-1 --output results.csv --plot results.png
    syssimx simulate Feedthrough.fmu --input signals.csv --tolerance 1e-8
    syssimx run system.yaml --tf 10 --dt 0.01 -o results.csv
    syssimx describe system.yaml
    syssimx run system.ssp --algorithm jacobi
    syssimx sweep system.yaml --param P.theta0=0.1:0.5:50 --param P.L=0.5,0.6 -o out.nc
    syssimx --version

An FMU argument is a path to a .fmu file or the name of a bundled FMU. Bad usage exits with
code 2, a failure while running with code 1; both print one clear line on stderr.

One module per command (`info`, `fmu_list`, `simulate`, `run`, `describe`, `sweep`), each
adding its parser and its function; `main` puts them together.
"""

from .main import build_parser, main

__all__ = ["build_parser", "main"]
