#!/usr/bin/python3
"""A tracked car's heading of travel from its own points, to judge a tracker's heading on real data
that carries no object labels (KITTI raw's tracklets are not in ../shared/data).

For each pair of sweeps (f, f+K) the car's points (within --radius-m of the track's centre in
tracks.csv, between its box's heights) are put in the map frame with the run's trajectory.tum and
aligned by 2D point-to-point ICP (nearest neighbours, closed-form rigid fit: Arun et al. 1987). The
transform moves the track's centre along the chord of the car's path: atan2 of that displacement is the
heading at the pair's mid-time, from the car's points and not from the boxes the tracker fits (the
centre enters only through the rotation: a centre d metres off moves the heading by about the pair's
rotation times d over the chord). Pairs with fewer
than --min-pairs ICP correspondences (a car half hidden, other objects in the radius) are left out.

usage: car_motion_oracle.py --bins KITTI/velodyne --track ID RUN [RUN[:ID] ...]
Every RUN is a roadslam-map output folder of the same sweeps; the first one's trajectory and track
select the points, and each one's heading_rad and speed_mps are scored against the oracle (median /
mean / max error). RUN:ID names the same car's track in a run that numbered it otherwise.
Only KITTI .bin sweeps (x, y, z, reflectance float32) are read.
"""
import argparse
import collections
import csv
import math
import statistics
import struct
import sys


def load_poses(run):
    poses = []
    with open(run + '/trajectory.tum') as f:
        for line in f:
            if line.startswith('#') or not line.strip():
                continue
            _, x, y, z, qx, qy, qz, qw = map(float, line.split())
            R = [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
                 [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
                 [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]]
            poses.append((R, (x, y, z)))
    return poses


def load_track(run, track):
    with open(run + '/tracks.csv') as f:
        return {int(r['frame']): r for r in csv.DictReader(f) if r['track_id'] == track}


def car_points(bins, frame, pose, row, radius):
    R, T = pose
    cx, cy = float(row['x']), float(row['y'])
    z_lo, z_hi = float(row['z_min']) - 0.05, float(row['z_max']) + 0.3  # the box's heights: no road
    with open('%s/%06d.bin' % (bins, frame), 'rb') as f:
        data = f.read()
    out = []
    for x, y, z, _ in struct.iter_unpack('ffff', data):
        X = R[0][0] * x + R[0][1] * y + R[0][2] * z + T[0]
        Y = R[1][0] * x + R[1][1] * y + R[1][2] * z + T[1]
        Z = R[2][0] * x + R[2][1] * y + R[2][2] * z + T[2]
        if (X - cx) ** 2 + (Y - cy) ** 2 < radius * radius and z_lo < Z < z_hi:
            out.append((X, Y))
    return out


def icp2d(src, dst, cell=0.5, iterations=40):
    """Rigid (theta, tx, ty) taking src onto dst, and the correspondences of the last step."""
    grid = collections.defaultdict(list)
    for p in dst:
        grid[(math.floor(p[0] / cell), math.floor(p[1] / cell))].append(p)
    th = 0.0
    tx = sum(p[0] for p in dst) / len(dst) - sum(p[0] for p in src) / len(src)
    ty = sum(p[1] for p in dst) / len(dst) - sum(p[1] for p in src) / len(src)
    pairs = []
    for _ in range(iterations):
        c, s = math.cos(th), math.sin(th)
        pairs = []
        for p in src:
            q = (c * p[0] - s * p[1] + tx, s * p[0] + c * p[1] + ty)
            kx, ky = math.floor(q[0] / cell), math.floor(q[1] / cell)
            best, best_d2 = None, cell * cell
            for dx in (-1, 0, 1):
                for dy in (-1, 0, 1):
                    for d in grid.get((kx + dx, ky + dy), ()):
                        d2 = (d[0] - q[0]) ** 2 + (d[1] - q[1]) ** 2
                        if d2 < best_d2:
                            best, best_d2 = d, d2
            if best:
                pairs.append((p, best))
        if len(pairs) < 3:
            return None
        n = len(pairs)
        ax, ay = sum(p[0] for p, _ in pairs) / n, sum(p[1] for p, _ in pairs) / n
        bx, by = sum(q[0] for _, q in pairs) / n, sum(q[1] for _, q in pairs) / n
        sxx = sum((p[0] - ax) * (q[0] - bx) + (p[1] - ay) * (q[1] - by) for p, q in pairs)
        sxy = sum((p[0] - ax) * (q[1] - by) - (p[1] - ay) * (q[0] - bx) for p, q in pairs)
        prev = (th, tx, ty)
        th = math.atan2(sxy, sxx)
        c, s = math.cos(th), math.sin(th)
        tx, ty = bx - (c * ax - s * ay), by - (s * ax + c * ay)
        if abs(th - prev[0]) < 1e-7 and abs(tx - prev[1]) < 1e-6 and abs(ty - prev[2]) < 1e-6:
            break  # the correspondences no longer change
    return th, tx, ty, len(pairs)


def main():
    try:
        run()
    except OSError as e:
        sys.exit('car_motion_oracle: %s: %s' % (e.filename, e.strerror))
    except (KeyError, ValueError) as e:
        sys.exit('car_motion_oracle: a malformed trajectory.tum or tracks.csv: %s' % e)


def run():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--bins', required=True, help='folder of KITTI NNNNNN.bin sweeps')
    ap.add_argument('--track', required=True, help='track_id in tracks.csv')
    ap.add_argument('--step', type=int, default=3, help='sweeps between the aligned pair [-]')
    ap.add_argument('--radius-m', type=float, default=3.0, help="points this close to the track's centre [m]")
    ap.add_argument('--min-pairs', type=int, default=400, help='ICP correspondences a pair needs [-]')
    ap.add_argument('--dt-s', type=float, default=0.1, help='time between sweeps [s]')
    ap.add_argument('runs', nargs='+')
    a = ap.parse_args()
    # RUN:ID names the car's track in a run whose ids differ (the first run's id is --track)
    runs = [(r.rsplit(':', 1)[0], r.rsplit(':', 1)[1]) if ':' in r else (r, a.track) for r in a.runs]
    a.runs = [r for r, _ in runs]
    poses = load_poses(a.runs[0])
    tracks = [load_track(run, track) for run, track in runs]
    for (run, track), t in zip(runs, tracks):
        if not t:
            sys.exit('%s/tracks.csv: no track %s' % (run, track))
    rows = tracks[0]
    headings = [{f: float(r['heading_rad']) for f, r in t.items()} for t in tracks]
    speeds = [{f: float(r['speed_mps']) for f, r in t.items()} for t in tracks]
    print('f0  f1  oracle_rad  speed_mps  pairs  ' + '  '.join('heading[%d]' % k for k in range(len(a.runs))))
    cache = {}

    def points(frame):  # each sweep is the end of one pair and the start of the next: read it once
        if frame not in cache:
            cache[frame] = car_points(a.bins, frame, poses[frame], rows[frame], a.radius_m)
        return cache[frame]

    errors = [[] for _ in a.runs]
    speed_errors = [[] for _ in a.runs]
    for f in sorted(rows):
        g = f + a.step
        if g not in rows or g >= len(poses):
            continue
        src, dst = points(f), points(g)
        if len(src) < a.min_pairs or len(dst) < a.min_pairs:
            continue
        res = icp2d(src, dst)
        if not res or res[3] < a.min_pairs:
            continue
        th, tx, ty, n = res
        # the chord of the track's centre under the points' rigid motion: in a turn, points off the car's
        # centre move off its heading by the rotation times their offset (the visible points' centroid, a
        # metre off, gave 0.016 rad in a 0.15 rad/s turn)
        cx, cy = float(rows[f]['x']), float(rows[f]['y'])
        c, s = math.cos(th), math.sin(th)
        mx, my = c * cx - s * cy + tx - cx, s * cx + c * cy + ty - cy
        oracle = math.atan2(my, mx)
        # the sweep at the chord's mid-time (even steps) or the two around it (odd steps)
        mid = [f + a.step // 2] if a.step % 2 == 0 else [f + a.step // 2, f + a.step // 2 + 1]
        line = '%d %d %+.4f %.2f %d' % (f, g, oracle, math.hypot(mx, my) / (a.step * a.dt_s), n)
        for k, h in enumerate(headings):
            if all(m in h for m in mid):
                m = math.atan2(sum(math.sin(h[i]) for i in mid), sum(math.cos(h[i]) for i in mid))
                errors[k].append(abs(math.remainder(m - oracle, 2 * math.pi)))
                speed_errors[k].append(abs(sum(speeds[k][i] for i in mid) / len(mid) - math.hypot(mx, my) / (a.step * a.dt_s)))
                line += '  %+.4f' % m
        print(line)
    print('\nrun  pairs  heading error median / mean / max [rad]  speed error median / mean / max [m/s]')
    for run, e, v in zip(a.runs, errors, speed_errors):
        if e:
            print('%s  %d  %.3f / %.3f / %.3f  %.2f / %.2f / %.2f' % (run, len(e), statistics.median(e), statistics.mean(e), max(e),
                                                             statistics.median(v), statistics.mean(v), max(v)))
        else:
            print('%s  0  (no pair)' % run)


if __name__ == '__main__':
    main()
