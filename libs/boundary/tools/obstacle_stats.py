#!/usr/bin/python3
"""Obstacle figures of a roadslam-bounds run (boundaries.jsonl): obstacles and their points per sweep,
sides found, and, with the simulator's gt_objects.json (the run posed by its gt_trajectory.tum), the
moving cars: a car (>= MIN_RETURNS returns, within MAX_RANGE_M) is found when an obstacle's centre
lies within 1 m of its centre, and split when the centres of two or more lie inside its footprint.

usage: obstacle_stats.py RUN_DIR [GT_OBJECTS_JSON]"""
import json
import math
import statistics
import sys

MIN_RETURNS, MAX_RANGE_M = 20, 30.0


def frames(run):
    with open(run + "/boundaries.jsonl") as f:
        return [json.loads(line) for line in f if line.strip()]


def car_stats(fr, gt_path):
    gt = json.load(open(gt_path))["moving_cars"]
    seen = found = split = 0
    err, length_err = [], []
    for f in fr:
        T = f["T_map_lidar"]  # row-major 4x4
        R = [[T[0], T[1], T[2]], [T[4], T[5], T[6]], [T[8], T[9], T[10]]]
        t = [T[3], T[7], T[11]]
        for car in gt:
            row = min(car["track"], key=lambda r: abs(r[0] - f["stamp_s"]))
            if abs(row[0] - f["stamp_s"]) > 0.06 or row[5] < MIN_RETURNS or row[6] > MAX_RANGE_M:
                continue
            d = [row[1] - t[0], row[2] - t[1], row[3] + 0.8 - t[2]]  # centre in the lidar frame: R^T d
            x = sum(R[k][0] * d[k] for k in range(3))
            y = sum(R[k][1] * d[k] for k in range(3))
            yaw = row[4] - math.atan2(R[1][0], R[0][0])
            seen += 1
            best = None
            inside = 0
            for o in f["obstacles"]:
                cx, cy = o["center"]
                dist = math.hypot(cx - x, cy - y)
                u = (cx - x) * math.cos(yaw) + (cy - y) * math.sin(yaw)
                v = -(cx - x) * math.sin(yaw) + (cy - y) * math.cos(yaw)
                inside += abs(u) <= 0.5 * car["length_m"] and abs(v) <= 1.0
                if best is None or dist < best[0]:
                    best = (dist, o)
            split += inside >= 2
            if best and best[0] <= 1.0:
                found += 1
                err.append(best[0])
                length_err.append(abs(best[1]["length_m"] - car["length_m"]))
    med = lambda v: statistics.median(v) if v else float("nan")
    return (f"GT car-sweeps {seen}: found {found} ({100.0 * found / max(seen, 1):.1f} %), split {split}, "
            f"centre error median {med(err):.3f} m, length error median {med(length_err):.3f} m")


def main():
    run = sys.argv[1]
    fr = frames(run)
    n = len(fr)
    obst = [len(f["obstacles"]) for f in fr]
    pts = [sum(o["points"] for o in f["obstacles"]) for f in fr]
    labelled = [f["counts"]["obstacle"] for f in fr]
    left = sum(f["left"]["found"] for f in fr)
    right = sum(f["right"]["found"] for f in fr)
    print(f"{run}: {n} sweeps, obstacles {statistics.mean(obst):.1f} per sweep, points in them "
          f"{sum(pts) / max(sum(labelled), 1) * 100:.1f} % of the obstacle-labelled, left found {100.0 * left / n:.1f} %, "
          f"right {100.0 * right / n:.1f} %, ms {statistics.mean(f['ms'] for f in fr):.1f}")
    if len(sys.argv) > 2:
        print("  " + car_stats(fr, sys.argv[2]))


if __name__ == "__main__":
    main()
