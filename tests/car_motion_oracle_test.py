#!/usr/bin/python3
"""scripts/car_motion_oracle.py on a synthetic drive whose car's heading is known exactly: a rigid car
(an L of points: rear face and left side, seen from the sensor's side, with ground points under it)
drives a circle arc; the sensor moves too (the run's trajectory carries its pose). The oracle must give
the car's chord heading within 0.012 rad (the tracks' centres are 0.36 m off the car's: 0.009 rad in
this turn) and score a run whose heading_rad is the truth at that error and a run 0.1 rad off at 0.1 rad. usage: car_motion_oracle_test.py SCRIPT"""
import atexit
import math
import os
import random
import shutil
import struct
import subprocess
import sys
import tempfile

script = sys.argv[1]
random.seed(1)
R_turn, v, dt, n = 40.0, 6.0, 0.1, 12  # a 40 m radius left turn at 6 m/s, 2 s
omega = v / R_turn


def car_pose(k):
    """Centre (x, y) and yaw of the car at sweep k, map frame: a circle arc from (10, -5) heading 0.3 rad."""
    yaw0 = 0.3
    a = yaw0 + omega * k * dt
    cx0, cy0 = 10 - R_turn * math.sin(yaw0), -5 + R_turn * math.cos(yaw0)
    return cx0 + R_turn * math.sin(a), cy0 - R_turn * math.cos(a), a


def sensor_pose(k):
    return 2.0 + 3.0 * k * dt, -12.0, 0.05 * k * dt  # x, y, yaw of the lidar in the map frame


def car_points():
    """Body-frame points of a 4.5 x 1.8 m car's rear face and right side, 0.3-1.4 m up (2 cm noise)."""
    pts = []
    for i in range(30):
        y = -0.9 + 1.8 * i / 29
        for z in (0.3, 0.8, 1.4):
            pts.append((-2.25, y, z))
    for i in range(75):
        x = -2.25 + 4.5 * i / 74
        for z in (0.3, 0.8, 1.4):
            pts.append((x, -0.9, z))
    return pts


d = tempfile.mkdtemp(prefix='oracle_test_')
atexit.register(shutil.rmtree, d, True)
bins, run_true, run_off = os.path.join(d, 'velodyne'), os.path.join(d, 'true'), os.path.join(d, 'off')
for p in (bins, run_true, run_off):
    os.makedirs(p)
body = car_points()
for run, bias in ((run_true, 0.0), (run_off, 0.1)):
    with open(run + '/trajectory.tum', 'w') as f:
        f.write('# t x y z qx qy qz qw\n')
        for k in range(n):
            sx, sy, sa = sensor_pose(k)
            f.write('%.3f %.6f %.6f 0 0 0 %.9f %.9f\n' % (k * dt, sx, sy, math.sin(sa / 2), math.cos(sa / 2)))
    with open(run + '/tracks.csv', 'w') as f:
        f.write('frame,stamp_s,track_id,x,y,vx,vy,speed_mps,heading_rad,length_m,width_m,z_min,z_max,moving,hits,misses,age_s\n')
        for k in range(n):
            cx, cy, a = car_pose(k)
            f.write('%d,%.3f,7,%.4f,%.4f,0,0,%.2f,%.6f,4.5,1.8,0.3,1.4,1,%d,0,%.1f\n' % (k, k * dt, cx + 0.3, cy - 0.2, v, a + bias, k + 1, k * dt))
for k in range(n):
    cx, cy, a = car_pose(k)
    sx, sy, sa = sensor_pose(k)
    with open('%s/%06d.bin' % (bins, k), 'wb') as f:
        world = [(cx + math.cos(a) * x - math.sin(a) * y, cy + math.sin(a) * x + math.cos(a) * y, z) for x, y, z in body]
        world += [(cx + random.uniform(-3, 3), cy + random.uniform(-3, 3), 0.0) for _ in range(100)]  # road
        for X, Y, Z in world:
            dx, dy = X - sx, Y - sy
            x, y = math.cos(sa) * dx + math.sin(sa) * dy, -math.sin(sa) * dx + math.cos(sa) * dy
            f.write(struct.pack('ffff', x + random.gauss(0, 0.02), y + random.gauss(0, 0.02), Z, 0.0))

out = subprocess.run(['/usr/bin/python3', script, '--bins', bins, '--track', '7', '--min-pairs', '100', run_true, run_off],
                     capture_output=True, text=True)
print(out.stdout, out.stderr)
if out.returncode != 0:
    sys.exit('oracle failed')
rows = [l.split() for l in out.stdout.splitlines() if l[:1].isdigit()]
if len(rows) < n - 3 - 2:
    sys.exit('only %d pairs scored' % len(rows))
worst = 0.0
for f0, f1, oracle, speed, pairs, *_ in rows:
    chord = math.atan2(car_pose(int(f1))[1] - car_pose(int(f0))[1], car_pose(int(f1))[0] - car_pose(int(f0))[0])
    worst = max(worst, abs(math.remainder(float(oracle) - chord, 2 * math.pi)))
    if abs(float(speed) - v) > 0.2:
        sys.exit('pair %s-%s: speed %s, truth %.2f' % (f0, f1, speed, v))
print('largest oracle error against the chord: %.4f rad' % worst)
summary = {l.split()[0]: l.split() for l in out.stdout.splitlines() if l.startswith(d)}
med_true = float(summary[run_true][2])
med_off = float(summary[run_off][2])
print('median error: true heading %.4f, 0.1 rad off %.4f' % (med_true, med_off))
speed_med_true = float(summary[run_true][7])  # the speed error's median (the chord's speed against speed_mps)
print('median speed error: %.3f m/s' % speed_med_true)
if worst > 0.012 or med_true > 0.012 or abs(med_off - 0.1) > 0.012 or speed_med_true > 0.15:
    sys.exit('FAILED')
