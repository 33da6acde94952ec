#!/usr/bin/python3
"""Independent oracle: decode the first N frames of a candump log on can0 with python3-canmatrix and
print "frame_index MESSAGE.SIGNAL raw_value" for every signal (used by test_real_data.cpp)."""
import contextlib
import sys

import canmatrix
import canmatrix.formats


def main():
    dbc, log, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
    with contextlib.redirect_stdout(sys.stderr):  # canmatrix prints its DBC parse complaints to stdout
        db = canmatrix.formats.loadp_flat(dbc)
    with open(log) as f:
        for i, line in enumerate(f):
            if i >= n:
                break
            parts = line.split()
            if len(parts) < 3 or parts[1] != "can0":
                continue
            ident, data = parts[2].split("#", 1)
            ext = len(ident) == 8
            frame = db.frame_by_id(canmatrix.ArbitrationId(int(ident, 16), extended=ext))
            if frame is None:
                continue
            payload = bytes.fromhex(data)
            if len(payload) < frame.size:
                continue
            for name, dec in frame.decode(payload).items():
                print(i, f"{frame.name}.{name}", int(dec.raw_value))


if __name__ == "__main__":
    main()
