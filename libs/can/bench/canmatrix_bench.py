#!/usr/bin/python3
"""Peer timing for bench_decode.cpp: decodes the same candump log with python3-canmatrix, for the
same MESSAGE.SIGNAL set, and prints the rate in frames per second (all frames of the log, as the
C++ benchmark counts them). Log parsing is outside the timed loop, as in the C++ benchmark.

usage: canmatrix_bench.py DBC LOG MSG.SIG,MSG.SIG,...
"""
import sys
import time

import canmatrix
import canmatrix.formats


def main():
    dbc, log, wanted = sys.argv[1], sys.argv[2], sys.argv[3].split(",")
    db = canmatrix.formats.loadp_flat(dbc)
    by_msg = {}
    for name in wanted:
        msg, sig = name.split(".", 1)
        by_msg.setdefault(msg, []).append(sig)
    plan = {}  # (id, extended) -> (canmatrix frame, signal names)
    for msg, sigs in by_msg.items():
        fr = db.frame_by_name(msg)
        plan[(fr.arbitration_id.id, fr.arbitration_id.extended)] = (fr, sigs)
    frames = []
    with open(log) as f:
        for line in f:
            parts = line.split()
            ident, data = parts[2].split("#", 1)
            frames.append((int(ident, 16), len(ident) == 8, bytes.fromhex(data)))
    sink = 0.0
    t0 = time.perf_counter()
    for ident, ext, payload in frames:
        p = plan.get((ident, ext))
        if p is None or len(payload) < p[0].size:
            continue
        decoded = p[0].decode(payload)
        for s in p[1]:
            sink += float(decoded[s].phys_value)
    dt = time.perf_counter() - t0
    print(f"{len(frames) / dt:.1f}")
    print(f"# {len(frames)} frames in {dt:.3f} s, checksum {sink:.3f}", file=sys.stderr)


if __name__ == "__main__":
    main()
