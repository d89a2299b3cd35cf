"""A run directory: config.toml, series.csv, run.pvd and snapshots/*.vtu.

The VTU files orodem writes (src/orodem/io/vtu_writer.cpp) are VTK XML
UnstructuredGrid files with raw appended little-endian data and UInt64 block
headers; they are read here directly with numpy, so VTK is not needed.
"""

import csv
import math
import os
import tomllib
import xml.etree.ElementTree as ET

import numpy as np

_MAX_PVD_BYTES = 64 << 20  # as orodem's reader: far beyond the 1e5-output limit

_VTK_TYPES = {
    "Int8": np.int8, "UInt8": np.uint8, "Int16": np.int16, "UInt16": np.uint16,
    "Int32": np.int32, "UInt32": np.uint32, "Int64": np.int64, "UInt64": np.uint64,
    "Float32": np.float32, "Float64": np.float64,
}


def read_series(path):
    """series.csv as a dict of numpy float arrays by column name (NaN kept)."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    if not rows:
        raise ValueError(f"{path}: empty, not an orodem series.csv")
    header, data = rows[0], rows[1:]
    out = {}
    for k, name in enumerate(header):
        out[name] = np.array([float(r[k]) if k < len(r) and r[k] != "" else math.nan for r in data])
    return out


def read_vtu(path):
    """The point data of an orodem VTU: 'x', 'y' (the points) and every point
    array by name; arrays of 3 components (velocity) have shape (n, 3)."""
    if not os.path.isfile(path):  # a device (/dev/zero) or FIFO would never end or block
        raise ValueError(f"{path}: not a regular file; not a VTU written by orodem")
    with open(path, "rb") as f:
        raw = f.read()
    marker = raw.find(b"<AppendedData")
    if marker < 0:
        raise ValueError(f"{path}: no appended data; not a VTU written by orodem")
    start = raw.index(b"_", raw.index(b">", marker)) + 1  # the data begin after '_'
    head = raw[:marker].decode("utf-8") + "</VTKFile>"
    root = ET.fromstring(head)
    if root.get("byte_order") != "LittleEndian" or root.get("header_type") != "UInt64":
        raise ValueError(f"{path}: expected little-endian data with UInt64 headers")
    piece = root.find("UnstructuredGrid/Piece")
    n = int(piece.get("NumberOfPoints"))

    def array(el):
        off = start + int(el.get("offset"))
        nbytes = int(np.frombuffer(raw, dtype="<u8", count=1, offset=off)[0])
        dtype = np.dtype(_VTK_TYPES[el.get("type")]).newbyteorder("<")
        a = np.frombuffer(raw, dtype=dtype, count=nbytes // dtype.itemsize, offset=off + 8).copy()
        comps = int(el.get("NumberOfComponents", "1"))
        return a.reshape(-1, comps) if comps > 1 else a

    out = {}
    points = array(piece.find("Points/DataArray"))
    if points.shape[0] != n:
        raise ValueError(f"{path}: {points.shape[0]} points, the header says {n}")
    out["x"], out["y"] = points[:, 0].copy(), points[:, 1].copy()
    for el in piece.find("PointData"):
        out[el.get("Name")] = array(el)
    for el in root.findall("UnstructuredGrid/FieldData/DataArray"):  # S, step, time (orodem writes them)
        v = array(el)
        out[el.get("Name")] = v[0] if v.size == 1 else v
    return out


def read_faults(path):
    """faults.csv as a dict of numpy arrays by column name: `vergence` as
    strings ("pro" | "retro"), the other columns as floats."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    if not rows or rows[0][:3] != ["S", "id", "vergence"]:
        raise ValueError(f"{path}: not an orodem faults.csv")
    header, data = rows[0], rows[1:]
    return {name: (np.array([r[k] for r in data]) if name == "vergence"
                   else np.array([float(r[k]) for r in data], dtype=float))
            for k, name in enumerate(header)}


class Run:
    """One run directory. Attributes: path, config (dict), series (dict of
    arrays; empty when series.csv is absent), outputs (list of S), faults
    (dict of arrays from faults.csv, one row per known fault per output;
    None when the run has no fault table)."""

    def __init__(self, path):
        self.path = os.fspath(path)
        cfg = os.path.join(self.path, "config.toml")
        if not os.path.exists(cfg):
            raise FileNotFoundError(f"{self.path}: not an orodem run directory (no config.toml)")
        with open(cfg, "rb") as f:
            self.config = tomllib.load(f)
        series = os.path.join(self.path, "series.csv")
        self.series = read_series(series) if os.path.exists(series) else {}
        faults = os.path.join(self.path, "faults.csv")
        self.faults = read_faults(faults) if os.path.exists(faults) else None
        self._snapshots = self._read_pvd()
        self.outputs = [s for s, _ in self._snapshots]

    def _read_pvd(self):
        pvd = os.path.join(self.path, "run.pvd")
        if not os.path.exists(pvd):
            return []
        if os.path.getsize(pvd) > _MAX_PVD_BYTES:
            raise ValueError(f"{pvd}: larger than {_MAX_PVD_BYTES >> 20} MiB, not an orodem run.pvd")
        root = ET.parse(pvd).getroot()
        out = []
        for d in root.iter("DataSet"):
            entry = d.get("file") or ""
            # Entries name files inside the run directory (as orodem's own reader demands).
            if not entry or os.path.isabs(entry) or ".." in entry.replace("\\", "/").split("/"):
                raise ValueError(f"{pvd}: entry {entry!r} is not a file inside the run directory")
            out.append((float(d.get("timestep")), os.path.join(self.path, entry)))
        return out

    def snapshot_path(self, S):
        """The file of the snapshot whose S is nearest the given one. An S beyond the run's snapshots (by more
        than half their spacing at that end) or NaN raises ValueError, as `orodem render --at` refuses it."""
        if not self._snapshots:
            raise LookupError(f"{self.path}: no snapshots (run.pvd)")
        Ss = sorted(e[0] for e in self._snapshots)
        tol_lo = 0.5 * (Ss[1] - Ss[0]) if len(Ss) > 1 else 0.5
        tol_hi = 0.5 * (Ss[-1] - Ss[-2]) if len(Ss) > 1 else 0.5
        if not (Ss[0] - tol_lo <= S <= Ss[-1] + tol_hi):
            raise ValueError(f"{self.path}: S = {S}: the run's snapshots are at S = {Ss[0]:.2f} to {Ss[-1]:.2f}")
        return min(self._snapshots, key=lambda e: abs(e[0] - S))[1]

    def snapshot(self, S):
        """The snapshot nearest S as a dict of numpy arrays (read_vtu)."""
        return read_vtu(self.snapshot_path(S))

    def __repr__(self):
        exp = self.config.get("run", {}).get("experiment", "?")
        return f"<orodem.Run {self.path!r}: {exp}, {len(self.outputs)} snapshots>"


def open_run(path):
    """The run directory at path (see Run)."""
    return Run(path)
