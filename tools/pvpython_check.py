#!/usr/bin/env pvpython
"""Check that ParaView opens Talus output: load an HDF5 (H5Part) file, its XDMF
sidecar (.xmf) and/or a .pvd series with ParaView's own readers and print, for the first and last
time step, the particle count and the range of a field.

Run it with ParaView's Python (Debian package 'paraview' ships pvpython):
  pvpython tools/pvpython_check.py out/dam_break.h5part out/dam_break.xmf out/dam_break.pvd --field pressure
  pvpython tools/pvpython_check.py out/dam_break.h5part --expect-points 65000 --expect-steps 51

Exit status: 0 when every file loaded (and matched the expectations given),
1 when one did not, 77 (the 'skipped' code of ctest and automake) when
ParaView's Python modules are not available, unless --require is given.
"""
import argparse
import os
import sys


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                epilog="\n\n".join(__doc__.split("\n\n")[1:]),
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("files", nargs="+",
                   help=".h5part (H5Part reader), .xmf (XDMF reader) and/or .pvd (PVD reader) files")
    p.add_argument("--field", default="pressure", help="point array whose range is printed (default pressure)")
    p.add_argument("--expect-points", type=int, help="fail unless the first step has this many particles")
    p.add_argument("--expect-steps", type=int, help="fail unless the file has this many time steps")
    p.add_argument("--require", action="store_true", help="fail (exit 1) instead of skipping without ParaView")
    return p.parse_args(argv)


def open_reader(simple, path):
    ext = os.path.splitext(path)[1].lower()
    if ext in (".h5part", ".h5", ".hdf5"):
        # The H5Part reader by name: with .h5 several readers would claim the file.
        reader = simple.H5PartReader(FileName=path)
    elif ext in (".xmf", ".xdmf"):
        reader = simple.XDMFReader(FileNames=[path])
    else:
        reader = simple.OpenDataFile(path)
    if reader is None:
        raise RuntimeError("no ParaView reader opens this file")
    return reader


def describe(simple, servermanager, path, field):
    reader = open_reader(simple, path)
    reader.UpdatePipelineInformation()
    times = list(getattr(reader, "TimestepValues", []) or [])
    if not isinstance(times, list):
        times = [times]
    results = []
    for t in ([times[0], times[-1]] if len(times) > 1 else (times or [None])):
        if t is None:
            reader.UpdatePipeline()
        else:
            reader.UpdatePipeline(t)
        data = servermanager.Fetch(reader)
        if data.IsA("vtkMultiBlockDataSet"):
            data = data.GetBlock(0)
        n = data.GetNumberOfPoints()
        array = data.GetPointData().GetArray(field)
        if array is None:
            names = [data.GetPointData().GetArrayName(k) for k in range(data.GetPointData().GetNumberOfArrays())]
            raise RuntimeError(f"no point array '{field}' (arrays: {', '.join(names)})")
        results.append((t, n, array.GetRange(-1 if array.GetNumberOfComponents() > 1 else 0)))
    simple.Delete(reader)
    return times, results


def main(argv=None):
    args = parse_args(argv)
    try:
        from paraview import simple, servermanager
    except ImportError:
        print("pvpython_check.py: ParaView's Python modules are not available (install Debian's 'paraview' "
              "and run this script with pvpython); skipped")
        return 1 if args.require else 77
    failed = False
    for path in args.files:
        try:
            times, results = describe(simple, servermanager, path, args.field)
        except Exception as e:  # report every file, then fail
            print(f"FAIL {path}: {e}")
            failed = True
            continue
        print(f"{path}: {len(times)} time steps" + (f", t = {times[0]:g} .. {times[-1]:g} s" if times else ""))
        for t, n, (lo, hi) in results:
            print(f"  t = {t if t is not None else 0:g} s: {n} particles, {args.field} in [{lo:.6g}, {hi:.6g}]")
        if args.expect_points is not None and results[0][1] != args.expect_points:
            print(f"FAIL {path}: {results[0][1]} particles, expected {args.expect_points}")
            failed = True
        if args.expect_steps is not None and len(times) != args.expect_steps:
            print(f"FAIL {path}: {len(times)} time steps, expected {args.expect_steps}")
            failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
