"""Ensembles: parameter sweeps and Monte Carlo runs of one system on Dask.

    from syssimx.ensemble import sweep

    if __name__ == "__main__":  # the worker processes import this script again
        result = sweep(build_system, {"P.theta0": [0.1, 0.2, 0.3]}, t0=0.0, tf=1.0, dt=0.05)
        result.dataset          # xarray: member x sample, parameters as coordinates
        result.write("out.nc")  # or .csv / .parquet: the tidy table

Each member runs in a Dask worker process (an embedded LocalCluster by default, or any
distributed cluster); a member that fails, hangs or crashes its worker is reported with its
reason and the others finish. Needs the `ensemble` extra (dask, distributed, xarray, and
scipy for .nc files).
"""

from .api import monte_carlo, sweep
from .member import MemberResult, MemberTask, run_member
from .members import parameter_sets, parse_values
from .result import EnsembleResult

__all__ = ["EnsembleResult", "MemberResult", "MemberTask", "monte_carlo", "parameter_sets",
           "parse_values", "run_member", "sweep"]
