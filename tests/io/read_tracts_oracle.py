#!/usr/bin/env python3
"""Independent reader for the tract writers' tests (tests/io/test_tract_writers.cpp).

  read_tracts_oracle.py FILE.trk   nibabel.streamlines.load (Debian python3-nibabel), points in RAS mm
  read_tracts_oracle.py FILE.trx   Python's zipfile (CRC-32 of every member checked) and struct, no TRX library

Prints "streamlines N", then per streamline "streamline K S", its K points "x y z" (%.9g: float32 exact) and
its S per-point scalars (.trk), each as "scalar NAME v1 ... vK"."""
import json
import struct
import sys
import zipfile


def emit(streamlines, scalars=None):
    print("streamlines %d" % len(streamlines))
    scalars = scalars or {}
    for i, points in enumerate(streamlines):
        print("streamline %d %d" % (len(points), len(scalars)))
        for p in points:
            print("%.9g %.9g %.9g" % tuple(float(c) for c in p))
        for name, values in scalars.items():
            print("scalar %s %s" % (name, " ".join("%.9g" % float(v) for v in values[i].reshape(-1))))


def read_trk(path):
    import nibabel.streamlines
    trk = nibabel.streamlines.load(path)
    streamlines = list(trk.streamlines)
    scalars = {name: trk.tractogram.data_per_point[name] for name in trk.tractogram.data_per_point.keys()}
    emit(streamlines, scalars)


def read_trx(path):
    with zipfile.ZipFile(path) as archive:
        bad = archive.testzip()
        if bad is not None:
            sys.exit("bad CRC-32 in " + bad)
        for info in archive.infolist():
            if info.compress_type != zipfile.ZIP_STORED:
                sys.exit(info.filename + " is not stored")
        header = json.loads(archive.read("header.json"))
        n, v = header["NB_STREAMLINES"], header["NB_VERTICES"]
        offsets = struct.unpack("<%dQ" % (n + 1), archive.read("offsets.uint64"))
        flat = struct.unpack("<%df" % (3 * v), archive.read("positions.3.float32"))
    if offsets[-1] != v or len(header["DIMENSIONS"]) != 3 or len(header["VOXEL_TO_RASMM"]) != 4:
        sys.exit("header and offsets disagree")
    points = [flat[3 * i:3 * i + 3] for i in range(v)]
    emit([points[offsets[s]:offsets[s + 1]] for s in range(n)])


if __name__ == "__main__":
    (read_trk if sys.argv[1].endswith(".trk") else read_trx)(sys.argv[1])
