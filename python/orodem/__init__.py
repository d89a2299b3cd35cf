"""Read orodem run directories from Python (numpy only; VTK not needed).

    import orodem
    r = orodem.open_run("runs/exp1")
    r.config["wedge"]["mu_bp"]          # the run's resolved config.toml, as a dict
    r.series["alpha_deg"]               # series.csv, one numpy array per column
    r.outputs                           # the S of every saved snapshot (run.pvd)
    snap = r.snapshot(r.outputs[-1])    # the snapshot nearest that S
    snap["x"], snap["y"], snap["radius"], snap["initial_depth"], snap["velocity"]
    r.faults["dip_deg"], r.faults["vergence"]   # faults.csv (None before the fault table)

Units and meanings of the snapshot arrays: docs/python.md.
"""

from .run import Run, open_run, read_faults, read_series, read_vtu

__all__ = ["Run", "open_run", "read_faults", "read_series", "read_vtu"]
__version__ = "0.1.0"
