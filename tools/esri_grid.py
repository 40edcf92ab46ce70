"""ESRI ASCII grids (.asc): the raster format of Talus' DEMs and run-out rasters.

read_asc(path) returns (values with the north row first, extent [x0, x1, y0, y1], nodata); a bad file ends the
program with a message naming it and exit code 2 (bad input). Values belong to cell centres: column c, row r (from the north) sits at
x0 + (c + 0.5) cell, y1 - (r + 0.5) cell."""
import sys

import numpy as np


def refuse(message):
    """Bad input: the message on stderr, exit code 2, nothing written."""
    sys.stderr.write("error: %s\n" % message)
    sys.exit(2)


def read_asc(path):
    header = {}
    try:
        with open(path) as f:
            for _ in range(6):
                pos = f.tell()
                line = f.readline().split()
                if len(line) != 2 or not line[0][0].isalpha():
                    f.seek(pos)
                    break
                header[line[0].lower()] = float(line[1])
            data = np.loadtxt(f, ndmin=2)
    except OSError as e:
        refuse(f"{path}: {e.strerror}")
    except ValueError as e:
        refuse(f"{path}: {e}")
    for key in ("ncols", "nrows", "cellsize"):
        if key not in header:
            refuse(f"{path}: header has no '{key}'")
    nc, nr, cell = int(header["ncols"]), int(header["nrows"]), header["cellsize"]
    if not cell > 0:
        refuse(f"{path}: cellsize must be > 0, got {cell}")
    if data.shape != (nr, nc):
        refuse(f"{path}: {data.shape[0]} x {data.shape[1]} values, header says {nr} x {nc}")
    x0 = header.get("xllcorner", header.get("xllcenter", 0.0) - cell / 2)
    y0 = header.get("yllcorner", header.get("yllcenter", 0.0) - cell / 2)
    return data, [x0, x0 + nc * cell, y0, y0 + nr * cell], header.get("nodata_value", -9999.0)


def write_asc(path, values, x0, y0, cell, nodata=-9999.0):
    """Writes values (north row first) with its lower-left corner at (x0, y0)."""
    nr, nc = values.shape
    with open(path, "w") as f:
        f.write(f"ncols {nc}\nnrows {nr}\nxllcorner {x0!r}\nyllcorner {y0!r}\ncellsize {cell!r}\n"
                f"NODATA_value {nodata!r}\n")
        for row in values:
            f.write(" ".join(f"{v:.6f}" for v in row) + "\n")

