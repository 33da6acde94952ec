#!/usr/bin/python3
"""How much of the ground-truth right (or left) curb 5-30 m ahead is backed by detected curb points,
per sweep and accumulated over the sweeps so far (map frame), from roadslam-bounds' boundaries.jsonl.

usage: curb_visibility.py GT_BOUNDARIES.json BOUNDARIES.jsonl [--side right|left] [--tol 0.3]
A curb point counts for the side when it lies 5-30 m ahead within --tol of the GT curb's lateral
offset at its x (vehicle frame); coverage = fraction of the 1 m stations 5-30 m ahead where the GT
curb exists that hold such a point (the eval's 'found' needs an estimate over half of them)."""
import argparse, bisect, json, math

def lateral_at(polys, x, side, max_lat=15.0):
    best = None
    for l in polys:
        for a, b in zip(l, l[1:]):
            if a[0] == b[0] or x < min(a[0], b[0]) or x > max(a[0], b[0]):
                continue
            y = a[1] + (b[1] - a[1]) * (x - a[0]) / (b[0] - a[0])
            if side * y <= 0 or abs(y) > max_lat:
                continue
            if best is None or abs(y) < abs(best):
                best = y
    return best

def to_vehicle(T, pts):
    # T row-major 4x4 T_map_lidar; inverse of the planar part is enough on the flat urban loop
    r = [[T[0], T[1]], [T[4], T[5]]]
    t = (T[3], T[7])
    out = []
    for p in pts:
        dx, dy = p[0] - t[0], p[1] - t[1]
        out.append((r[0][0] * dx + r[1][0] * dy, r[0][1] * dx + r[1][1] * dy))
    return out

def to_map(T, pts):
    return [(T[0] * x + T[1] * y + T[3], T[4] * x + T[5] * y + T[7]) for x, y in pts]

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("gt"); ap.add_argument("est")
    ap.add_argument("--side", default="right"); ap.add_argument("--tol", type=float, default=0.3)
    a = ap.parse_args()
    side = -1 if a.side == "right" else 1
    gt = json.load(open(a.gt))
    curbs = [l for r in gt["roads"] for k in ("left_curbs", "right_curbs") for l in r[k]]
    acc = []
    n = any_now = any_acc = half_now = half_acc = 0
    for line in open(a.est):
        f = json.loads(line)
        if "T_map_lidar" not in f:
            continue
        T = f["T_map_lidar"]
        acc += to_map(T, f.get("curb_points", []))
        tv = [c for c in curbs]
        gtv = []
        for l in tv:
            run = []
            for p in l + [None]:  # runs of vertices near the vehicle
                if p is not None and math.hypot(p[0] - T[3], p[1] - T[7]) < 60:
                    run.append(p)
                    continue
                if len(run) >= 2:
                    gtv.append(to_vehicle(T, run))
                run = []
        stations = [x for x in range(5, 31) if lateral_at(gtv, x, side) is not None]
        if not stations:
            continue
        n += 1
        cov = []
        for pts in (f.get("curb_points", []), to_vehicle(T, acc)):
            hit = set()
            for x, y in pts:
                if 4.5 <= x <= 30.5:
                    s = int(round(x))
                    yg = lateral_at(gtv, x, side)
                    if yg is not None and abs(y - yg) <= a.tol:
                        hit.add(s)
            cov.append(len(hit & set(stations)) / len(stations))
        any_now += cov[0] > 0; any_acc += cov[1] > 0
        half_now += cov[0] >= 0.5; half_acc += cov[1] >= 0.5
        print(f"{f['index']:4d} t={f['stamp_s'] - 1.7e9:6.2f} cov_sweep={cov[0]:.2f} cov_accum={cov[1]:.2f} found={f[a.side]['found']}")
    print(f"frames {n}: {a.side} curb points 5-30 m ahead in the sweep {any_now / n:.2f}, accumulated {any_acc / n:.2f}; "
          f"covering >= half the stations: sweep {half_now / n:.2f}, accumulated {half_acc / n:.2f}")

main()
