"""The Python reader against a real run made by the orodem binary
(ORODEM_EXE, else build/orodem), and against VTK's own reader where
python3-vtk9 is installed."""
import csv
import math
import os
import subprocess
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import orodem

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = os.environ.get("ORODEM_EXE", os.path.join(ROOT, "build", "orodem"))

TINY = """[run]
experiment = "exp1"
[wedge]
v = 0.3
s_max = 0.3
output_ds = 0.1
pro_margin = 5.0
retro_length = 3.0
[packing]
h0 = 6.0
cache_dir = "{cache}"
"""


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("orodem-python")
    cfg = tmp / "tiny.toml"
    cfg.write_text(TINY.format(cache=tmp / "cache"))
    out = tmp / "run"
    subprocess.run([EXE, "run", str(cfg), "--out", str(out), "--threads", "1"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return out


def test_config_series_and_outputs(run_dir):
    r = orodem.open_run(run_dir)
    assert r.config["run"]["experiment"] == "exp1"
    assert r.config["wedge"]["v"] == 0.3
    with open(run_dir / "series.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert set(r.series) == set(rows[0])
    assert len(r.series["S"]) == len(rows) == 4  # S = 0, 0.1, 0.2, 0.3
    for k, row in enumerate(rows):
        for name, text in row.items():
            want = float(text)
            got = r.series[name][k]
            assert (math.isnan(want) and math.isnan(got)) or got == want, (name, k)
    pvd = [float(d.get("timestep")) for d in ET.parse(run_dir / "run.pvd").getroot().iter("DataSet")]
    assert r.outputs == pvd
    assert r.outputs[-1] == pytest.approx(0.3, abs=1e-3)  # the last step reaches s_max to a step


def test_faults_table(run_dir):
    r = orodem.open_run(run_dir)
    with open(run_dir / "faults.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert r.faults is not None and set(r.faults) == set(rows[0] if rows else r.faults)
    assert len(r.faults["S"]) == len(rows)
    for k, row in enumerate(rows):
        assert r.faults["vergence"][k] == row["vergence"] in ("pro", "retro")
        assert r.faults["dip_deg"][k] == float(row["dip_deg"])


def test_snapshot_is_self_describing(run_dir):
    r = orodem.open_run(run_dir)
    for k, S in enumerate(r.outputs):
        s = r.snapshot(S)
        assert s["S"] == pytest.approx(S, abs=5e-7)  # run.pvd keeps 6 decimals
        assert s["step"] == int(r.series["step"][k])
        assert s["time"] == pytest.approx(r.series["time"][k], rel=1e-8)
        n = s["radius"].size
        assert s["x"].shape == s["y"].shape == (n,)
        assert s["velocity"].shape == (n, 3)
        assert sorted(s["id"]) == list(range(n))
    assert r.snapshot_path(0.26) == r.snapshot_path(0.3)  # the nearest S


def test_snapshot_equals_vtks_reading(run_dir):
    vtk = pytest.importorskip("vtk")
    from vtk.util.numpy_support import vtk_to_numpy
    r = orodem.open_run(run_dir)
    path = r.snapshot_path(r.outputs[-1])
    s = r.snapshot(r.outputs[-1])
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    pts = vtk_to_numpy(grid.GetPoints().GetData())
    assert np.array_equal(pts[:, 0], s["x"]) and np.array_equal(pts[:, 1], s["y"])
    pd = grid.GetPointData()
    assert pd.GetNumberOfArrays() == 16  # 10 per disc (fixed, asleep) + the interval's strain (4) + shear_strain_total + rel_disp_abs
    for k in range(pd.GetNumberOfArrays()):
        a = pd.GetArray(k)
        assert np.array_equal(vtk_to_numpy(a), s[a.GetName()]), a.GetName()
    # rel_disp is rel_disp_abs [m] over its largest value, the same division.
    assert s["rel_disp_abs"].max() > 0
    assert np.array_equal(s["rel_disp_abs"] / s["rel_disp_abs"].max(), s["rel_disp"])
    fd = grid.GetFieldData()
    assert {fd.GetArray(k).GetName(): fd.GetArray(k).GetValue(0) for k in range(3)} == {
        "S": s["S"], "step": s["step"], "time": s["time"]}


def test_what_is_not_a_run_is_refused(tmp_path):
    with pytest.raises(FileNotFoundError, match="not an orodem run directory"):
        orodem.open_run(tmp_path)
    bad = tmp_path / "x.vtu"
    bad.write_text("<VTKFile/>")
    with pytest.raises(ValueError, match="no appended data"):
        orodem.read_vtu(bad)


def test_snapshot_beyond_the_run_is_refused(run_dir):
    r = orodem.open_run(run_dir)
    last = r.outputs[-1]
    with pytest.raises(ValueError, match="snapshots are at S"):
        r.snapshot(last + 5.0)
    with pytest.raises(ValueError):
        r.snapshot(float("nan"))
    assert r.snapshot_path(last) == r.snapshot_path(last + 0.01)


def test_the_paths_of_a_run_with_surface(tmp_path):
    """A run with [surface] (erosion and both forelands filled): its snapshots carry each disc's
    birth_S, max_burial_depth and erosion_S, which agree with eroded.csv; a run without has none."""
    cfg = tmp_path / "surface.toml"
    cfg.write_text(TINY.format(cache=tmp_path / "cache").replace("s_max = 0.3", "s_max = 1.5")
                   .replace("pro_margin = 5.0", "pro_margin = 4.0")
                   + '[surface]\nlaw = "elevation"\nk = 2.0\nsediment = "both"\nbase_level = 0.3\n'
                   'sediment_rate = 0.5\nsediment_reserve = 20.0\n')
    out = tmp_path / "run"
    subprocess.run([EXE, "run", str(cfg), "--out", str(out), "--threads", "1", "--set", "wedge.output_ds=0.5"],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    r = orodem.open_run(out)
    s = r.snapshot(r.outputs[-1])
    birth, burial, eroded_at = s["birth_S"], s["max_burial_depth"], s["erosion_S"]
    assert birth.shape == burial.shape == eroded_at.shape == s["id"].shape
    deposited = birth > 0
    assert deposited.any() and (birth[deposited] <= r.outputs[-1] + 1e-9).all()
    assert np.isnan(birth).any()  # the reserve not yet deposited
    assert (burial[~np.isnan(birth)] >= 0).all()
    with open(out / "eroded.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert rows
    by_id = dict(zip(s["id"].tolist(), eroded_at.tolist()))
    for row in rows:
        assert by_id[int(row["id"])] == pytest.approx(float(row["S"]), abs=1e-6)
    assert np.isfinite(eroded_at).sum() == len(rows)


def test_a_run_without_surface_has_no_paths(run_dir):
    r = orodem.open_run(run_dir)
    s = r.snapshot(r.outputs[-1])
    assert "birth_S" not in s and "max_burial_depth" not in s and "erosion_S" not in s
