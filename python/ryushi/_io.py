"""Reading a run's output back: series.csv, the VTK particle files (.vtp, and .pvtp of a run on
several processes) and the .pvd collection."""
import csv
import os
import re
import xml.etree.ElementTree as ET

import numpy as np

_TYPES = {"Float64": "<f8", "Float32": "<f4", "Int64": "<i8", "Int32": "<i4", "UInt8": "u1",
          "UInt64": "<u8"}


def read_series(path, frame=False):
    """series.csv of a run as {column: NumPy array} (numbers as float64, other columns as
    strings), in the file's order; frame=True gives a pandas DataFrame instead."""
    if frame:
        import pandas
        return pandas.read_csv(path)
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        raise ValueError("%s: empty file (no header)" % path)
    header, body = rows[0], rows[1:]
    for i, r in enumerate(body):
        if len(r) != len(header):
            raise ValueError("%s:%d: %d values, the header has %d" % (path, i + 2, len(r),
                                                                      len(header)))
    out = {}
    for j, name in enumerate(header):
        col = [r[j] for r in body]
        try:
            out[name] = np.array([float(v) for v in col], dtype=np.float64)
        except ValueError:
            out[name] = np.array(col)
    return out


class Particles(dict):
    """The arrays of a particle file, {name: NumPy array}: "position" (n, 3; z is 0 in 2D, as
    ParaView expects), "velocity" (n, 3), "pressure", "density", "mass", "kind", "material",
    "id" and whatever fields the case wrote; .time is the simulated time of the file."""

    time = float("nan")


def _vtp_arrays(path):
    with open(path, "rb") as f:
        data = f.read()
    marker = data.find(b"<AppendedData")
    if marker < 0:
        raise ValueError("%s: not a VTK PolyData file with appended data" % path)
    start = data.index(b"_", marker) + 1
    head = data[:marker].decode()
    m = re.search(r'Name="TimeValue"[^>]*>([^<]*)<', head)
    out = Particles()
    out.time = float(m.group(1)) if m else float("nan")
    n = int(re.search(r'NumberOfPoints="(\d+)"', head).group(1))
    for tag in re.finditer(r"<DataArray ([^>]*?)/>", head):
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', tag.group(1)))
        if attrs.get("format") != "appended" or attrs["Name"] in ("connectivity", "offsets"):
            continue
        off = start + int(attrs["offset"])
        nbytes = int(np.frombuffer(data, "<u8", 1, off)[0])
        a = np.frombuffer(data, _TYPES[attrs["type"]], nbytes // np.dtype(
            _TYPES[attrs["type"]]).itemsize, off + 8)
        ncomp = int(attrs.get("NumberOfComponents", "1"))
        a = a.reshape(n, ncomp) if ncomp > 1 else a
        out["position" if attrs["Name"] == "Points" else attrs["Name"]] = a.copy()
    return out


def read_vtp(path):
    """The particles of an output file (.vtp, or .pvtp: the pieces of a run on several
    processes joined) as a Particles dict of NumPy arrays."""
    if not path.endswith(".pvtp"):
        return _vtp_arrays(path)
    root = ET.parse(path).getroot()
    folder = os.path.dirname(path)
    pieces = [_vtp_arrays(os.path.join(folder, p.get("Source"))) for p in root.iter("Piece")]
    out = Particles()
    t = root.find(".//FieldData/DataArray[@Name='TimeValue']")
    out.time = float(t.text) if t is not None else (pieces[0].time if pieces else float("nan"))
    for name in (pieces[0] if pieces else {}):
        out[name] = np.concatenate([p[name] for p in pieces])
    return out


def read_pvd(path):
    """The outputs of a run listed in its .pvd file: [(time, path of the particle file)]."""
    root = ET.parse(path).getroot()
    folder = os.path.dirname(path)
    return [(float(d.get("timestep")), os.path.join(folder, d.get("file")))
            for d in root.iter("DataSet")]
