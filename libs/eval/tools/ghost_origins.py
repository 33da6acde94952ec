#!/usr/bin/env python3
"""Where the ghost points of a roadslam-map run come from (the far trails of moving cars).

map.ply is the first keyframe point of every voxel_m voxel, keyframes in order (mapping::buildPointMap),
so rebuilding it from keyframes.bin gives each map point its keyframe (sweep) exactly. A map point is a
ghost when it lies in a moving GT car's box (grown by the margin, from the margin above its ground to its
roof) at a GT sample within 0.1 s of that sweep (the sweep's points were fired within 0.05 s of its
reference time); the box is carried into the map frame as roadslam-eval does (T_map_world(t) =
T_map_lidar(t) * T_world_lidar_gt(t)^-1). The sweep's objects.csv / tracks.csv rows then say what the
objects stage made of that car: an object near its centre, its confirmed track, the moving label, and
whether the point lay in the object's removal box. Standard library only (the checks are one-off).

usage: ghost_origins.py --gt SIM/gt_objects.json --gt-trajectory SIM/gt_trajectory.tum --run RUN
       [--voxel 0.2] [--margin 0.3] [--min-points 8] [--json OUT.json]
"""
import argparse
import bisect
import collections
import csv
import json
import math
import struct


def quat_to_rot(qx, qy, qz, qw):
    return [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
            [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
            [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]]


def read_tum(path):
    ts, poses = [], []
    for line in open(path):
        if line.startswith('#') or not line.strip():
            continue
        v = [float(x) for x in line.split()]
        ts.append(v[0])
        poses.append((v[4:8], v[1:4]))
    return ts, poses


def slerp(q0, q1, u):
    d = sum(a * b for a, b in zip(q0, q1))
    if d < 0:
        q1, d = [-x for x in q1], -d
    if d > 0.9995:
        q = [(1 - u) * a + u * b for a, b in zip(q0, q1)]
    else:
        th = math.acos(d)
        w0, w1 = math.sin((1 - u) * th) / math.sin(th), math.sin(u * th) / math.sin(th)
        q = [w0 * a + w1 * b for a, b in zip(q0, q1)]
    n = math.sqrt(sum(x * x for x in q))
    return [x / n for x in q]


def pose_at(tr, t):
    """As roadslam-eval's poseAt: linear translation, slerp rotation, clamped to the span."""
    ts, poses = tr
    t = min(max(t, ts[0]), ts[-1])
    k = min(len(ts) - 1, max(1, bisect.bisect_right(ts, t)))
    u = 0.0 if ts[k] == ts[k - 1] else min(1.0, max(0.0, (t - ts[k - 1]) / (ts[k] - ts[k - 1])))
    (q0, p0), (q1, p1) = poses[k - 1], poses[k]
    return quat_to_rot(*slerp(q0, q1, u)), [(1 - u) * a + u * b for a, b in zip(p0, p1)]


def apply(T, p):
    R, t = T
    return [R[i][0] * p[0] + R[i][1] * p[1] + R[i][2] * p[2] + t[i] for i in range(3)]


def apply_inv(T, p):
    R, t = T
    d = [p[i] - t[i] for i in range(3)]
    return [R[0][i] * d[0] + R[1][i] * d[1] + R[2][i] * d[2] for i in range(3)]


def read_keyframes(path):
    b = open(path, 'rb').read()
    assert b[:4] == b'RSKF', path
    n = struct.unpack_from('<Q', b, 8)[0]
    o = 16
    kfs = []
    for _ in range(n):
        frame, stamp, _path = struct.unpack_from('<Qdd', b, o)
        o += 24
        M = struct.unpack_from('<12d', b, o)
        o += 96
        npts = struct.unpack_from('<I', b, o)[0]
        o += 4
        pts = list(struct.iter_unpack('<3f', b[o:o + 12 * npts]))
        o += 12 * npts
        rows, cols = struct.unpack_from('<II', b, o)
        o += 8 + 4 * rows * cols
        R = [list(M[0:3]), list(M[4:7]), list(M[8:11])]
        kfs.append((frame, stamp, (R, [M[3], M[7], M[11]]), pts))
    return kfs


def read_csv_by_frame(path):
    out = collections.defaultdict(list)
    with open(path) as f:
        for row in csv.DictReader(f):
            out[int(row['frame'])].append(row)
    return out


def in_box(p, cx, cy, yaw, hl, hw, z0, z1):
    c, s = math.cos(yaw), math.sin(yaw)
    dx, dy = p[0] - cx, p[1] - cy
    return abs(c * dx + s * dy) <= hl and abs(-s * dx + c * dy) <= hw and z0 <= p[2] <= z1


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--gt', required=True)
    ap.add_argument('--gt-trajectory', required=True)
    ap.add_argument('--run', required=True)
    ap.add_argument('--voxel', type=float, default=0.2, help='[point_map] voxel_m of the run')
    ap.add_argument('--margin', type=float, default=0.3, help="ghost margin and [objects] removal_margin_m")
    ap.add_argument('--min-points', type=int, default=8, help='[objects] min_points of the run')
    ap.add_argument('--match', type=float, default=3.0, help='object-to-GT-car centre distance [m]')
    ap.add_argument('--json')
    a = ap.parse_args()

    gt = json.load(open(a.gt))
    gtt = read_tum(a.gt_trajectory)
    est = read_tum(a.run + '/trajectory.tum')
    odo = read_tum(a.run + '/trajectory_odometry.tum')
    objects = read_csv_by_frame(a.run + '/objects.csv')
    tracks = read_csv_by_frame(a.run + '/tracks.csv')
    ever_moving = set()
    first_moving = {}
    for fr, rows in tracks.items():
        for r in rows:
            if r['moving'] == '1':
                ever_moving.add(int(r['track_id']))
                tid = int(r['track_id'])
                first_moving[tid] = min(first_moving.get(tid, 1e30), float(r['stamp_s']))
    cars = gt['moving_cars']
    samples = []  # (t, car index, sample)
    for ci, c in enumerate(cars):
        for q in c['track']:
            samples.append((q[0], ci, q))
    samples.sort(key=lambda s: s[0])
    sample_ts = [s[0] for s in samples]

    kfs = read_keyframes(a.run + '/keyframes.bin')
    seen = set()
    n_map = 0
    rows = []
    for frame, stamp, T, pts in kfs:
        lo, hi = bisect.bisect_left(sample_ts, stamp - 0.1 - 1e-6), bisect.bisect_right(sample_ts, stamp + 0.1 + 1e-6)
        boxes = []
        for t, ci, q in samples[lo:hi]:
            c = cars[ci]
            Tg = pose_at(gtt, t)
            Tm = pose_at(est, t)
            centre = apply(Tm, apply_inv(Tg, q[1:4]))
            head = apply(Tm, apply_inv(Tg, [q[1] + math.cos(q[4]), q[2] + math.sin(q[4]), q[3]]))
            yaw = math.atan2(head[1] - centre[1], head[0] - centre[0])
            boxes.append((abs(t - stamp), ci, q, centre, yaw, c))
        boxes.sort(key=lambda b: b[0])
        for ql in pts:
            p = apply(T, ql)
            key = (math.floor(p[0] / a.voxel), math.floor(p[1] / a.voxel), math.floor(p[2] / a.voxel))
            if key in seen:
                continue
            seen.add(key)
            n_map += 1
            for dt, ci, q, centre, yaw, c in boxes:
                hl, hw = 0.5 * c['length_m'] + a.margin, 0.5 * c['width_m'] + a.margin
                if in_box(p, centre[0], centre[1], yaw, hl, hw, centre[2] + a.margin, centre[2] + c['height_m']):
                    rows.append((frame, stamp, ql, ci, q))
                    break
    print(f'map points rebuilt from keyframes.bin: {n_map}; ghosts made by a GT car within 0.1 s of their sweep: {len(rows)}')

    classes = collections.Counter()
    by_range = collections.defaultdict(collections.Counter)
    details = []
    for frame, stamp, ql, ci, q in rows:
        c = cars[ci]
        rng, ret = q[6], q[5]
        # the car at the sweep's time in the odometry's map frame (objects.csv's frame)
        Tg, To = pose_at(gtt, stamp), pose_at(odo, stamp)
        tr = c['track']
        # nearest samples bracket the sweep time: interpolate the car's centre
        ts = [s[0] for s in tr]
        k = min(len(ts) - 1, max(1, bisect.bisect_right(ts, stamp)))
        u = min(1.0, max(0.0, (stamp - ts[k - 1]) / (ts[k] - ts[k - 1])))
        cw = [(1 - u) * tr[k - 1][i] + u * tr[k][i] for i in (1, 2, 3)]
        car_odo = apply(To, apply_inv(Tg, cw))
        p_odo = apply(To, ql)
        best = None
        for o in objects.get(frame, []):
            d = math.hypot(float(o['cx']) - car_odo[0], float(o['cy']) - car_odo[1])
            if d <= a.match and (best is None or d < best[0]):
                best = (d, o)
        if ret < a.min_points:
            cls = f'1 car hit by < {a.min_points} points in that sweep'
        elif best is None:
            cls = '2 >= min_points returns, no object segmented there'
        else:
            o = best[1]
            tid = int(o['track_id'])
            moving = any(int(r['track_id']) == tid and r['moving'] == '1' for r in tracks.get(frame, []))
            inside = in_box(p_odo, float(o['cx']), float(o['cy']), float(o['yaw_rad']),
                            0.5 * float(o['length_m']) + a.margin, 0.5 * float(o['width_m']) + a.margin,
                            float(o['z_min']) - a.margin, float(o['z_max']) + a.margin)
            if tid < 0:
                cls = '3 object, no confirmed track'
            elif not moving and tid in ever_moving:
                cls = '4a confirmed track, labelled moving later'
            elif not moving:
                cls = '4b confirmed track, never labelled moving'
            elif not inside:
                cls = '5 moving track, point outside the object box'
            else:
                cls = '6 moving track, point inside the object box'
        rb = '<50' if rng < 50 else '50-80' if rng < 80 else '80-100' if rng < 100 else '>=100'
        classes[cls] += 1
        by_range[cls][rb] += 1
        details.append({'frame': frame, 't': stamp, 'car': c['id'], 'range_m': rng, 'returns': ret, 'class': cls,
                        'object_points': int(best[1]['points']) if best else 0})
    bins = ['<50', '50-80', '80-100', '>=100']
    print('| class | points | ' + ' | '.join('range ' + b + ' m' for b in bins) + ' |')
    print('|---|---|' + '---|' * len(bins))
    for cls in sorted(classes):
        print(f'| {cls} | {classes[cls]} | ' + ' | '.join(str(by_range[cls][b]) for b in bins) + ' |')
    ret_hist = collections.Counter()
    for d in details:
        r = d['returns']
        ret_hist['0' if r == 0 else '1-3' if r < 4 else '4-7' if r < 8 else '8-15' if r < 16 else '>=16'] += 1
    print('car returns in the ghost\'s sweep:', dict(ret_hist))
    sweeps = collections.Counter((d['frame'], d['car']) for d in details)
    print(f'(sweep, car) pairs that left ghosts: {len(sweeps)}')
    if a.json:
        json.dump({'map_points': n_map, 'ghosts': len(rows), 'classes': classes, 'by_range': by_range,
                   'details': details}, open(a.json, 'w'), indent=1)


if __name__ == '__main__':
    main()
