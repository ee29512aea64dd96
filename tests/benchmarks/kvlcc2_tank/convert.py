"""The KVLCC2 free-running tank tests as vesselid CSV files, at model scale (1:45.7, L 7 m).

Where they come from: SIMMAN 2008's KVLCC2 free-running tests, HSVA (13 zigzags, model scale,
0.05 s) and MARIN (4 zigzags and two 35 deg turning circles, full scale), as published with the
code of Alexandersson et al. (2022) in martinlarsalbert/System-identification-of-Vessel-
Manoeuvring-Models, data/01_raw; an unchanged copy is at ../shared/data/kvlcc2. They carry no
licence: read them, never commit them or what this script makes of them.

    /usr/bin/python3 tests/benchmarks/kvlcc2_tank/convert.py \
        --hsva ../shared/data/kvlcc2/kvlcc2_hsva/raw_data --marin ../shared/data/kvlcc2/kvlcc2 \
        --out /tmp/kvlcc2_tank

Columns written: t [s], x, y [m, earth-fixed], psi [deg], U [m/s], u, v [m/s], r [deg/s],
delta [deg], n [1/s], thrust [N] (HSVA only; empty for MARIN). Conversions:
* the rudder's sign: both basins log a positive angle for a turn to port; the MMG model's
  positive rudder turns to starboard (N_R > 0), so delta is negated;
* MARIN at full scale to model scale (Froude): lengths / 45.7, times and speeds / sqrt(45.7),
  rates * sqrt(45.7), propeller rpm / 60 * sqrt(45.7); its time column is printed with three
  significant digits, so time is rebuilt as i * 0.02 s (model scale);
* HSVA's columns (t, x0, y0, psi, u, v, p, r, delta, rev, thrust, torque) as logged, its
  velocities u, v body-fixed; MARIN's (t, x0, y0, phi, psi, xdot, ydot, p, r, delta, n) with
  earth-fixed xdot, ydot, turned into the body frame by psi;
* every record resampled to 0.1 s (every 2nd HSVA row, every 5th MARIN row) and its time
  starting at 0.
"""
import argparse
import glob
import math
import os
import sys

SCALE = 45.7
STEP = 0.1


def read_rows(path, skip):
    rows = []
    with open(path, encoding="cp1252") as f:
        for i, line in enumerate(f):
            if i < skip or not line.strip():
                continue
            rows.append([float(v) for v in line.split()])
    return rows


def write(path, rows):
    with open(path, "w") as f:
        f.write("t,x,y,psi,U,u,v,r,delta,n,thrust\n")
        for r in rows:
            f.write(",".join("" if v is None else "%.6g" % v for v in r) + "\n")


def hsva(folder, out):
    names = []
    for path in sorted(glob.glob(os.path.join(folder, "HSVA_CPMC_KVLCC2_Z_*.dat"))):
        raw = read_rows(path, 4)
        t0 = raw[0][0]
        rows = []
        for k in range(0, len(raw), int(round(STEP / 0.05))):
            t, x, y, psi, u, v, p, r, delta, rev, thrust = raw[k][:11]
            rows.append([t - t0, x, y, psi, math.hypot(u, v), u, v, r, -delta, rev, thrust])
        # Z_10_10_P -> hsva_z10_10p, Z_05_01 -> hsva_z05_01
        tag = os.path.basename(path)[len("HSVA_CPMC_KVLCC2_Z_"):-4].lower().replace("_p", "p")
        tag = tag.replace("_s", "s")
        name = "hsva_z" + tag
        write(os.path.join(out, name + ".csv"), rows)
        names.append((name, len(rows), rows[-1][0]))
    return names


def marin(folder, out):
    names = []
    root = math.sqrt(SCALE)
    runs = {"zz_10": "marin_z10", "zz_-10": "marin_zm10", "zz_20": "marin_z20",
            "zz_-20": "marin_zm20", "tc_35": "marin_tc35", "tc_-35": "marin_tcm35"}
    for src, name in runs.items():
        path = os.path.join(folder, "MARIN_FREE_KVLCC2_%s_m.dat" % src)
        if not os.path.exists(path):
            continue
        raw = read_rows(path, 3)
        rows = []
        every = int(round(STEP / 0.02))
        for k in range(0, len(raw), every):
            _, x, y, _, psi, xdot, ydot, _, r, delta, rpm = raw[k][:11]
            c, s = math.cos(math.radians(psi)), math.sin(math.radians(psi))
            u = (c * xdot + s * ydot) / root
            v = (-s * xdot + c * ydot) / root
            rows.append([k * 0.02, x / SCALE, y / SCALE, psi, math.hypot(u, v), u, v, r * root,
                         -delta, rpm / 60.0 * root, None])
        write(os.path.join(out, name + ".csv"), rows)
        names.append((name, len(rows), rows[-1][0]))
    return names


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--hsva", help="folder of HSVA_CPMC_KVLCC2_Z_*.dat")
    parser.add_argument("--marin", help="folder of MARIN_FREE_KVLCC2_*_m.dat")
    parser.add_argument("--out", required=True)
    a = parser.parse_args()
    if not a.hsva and not a.marin:
        sys.exit("give --hsva and/or --marin")
    os.makedirs(a.out, exist_ok=True)
    made = (hsva(a.hsva, a.out) if a.hsva else []) + (marin(a.marin, a.out) if a.marin else [])
    if not made:
        sys.exit("no records found in the folders given")
    for name, n, t in made:
        print("%-16s %5d rows  %6.1f s" % (name, n, t))


if __name__ == "__main__":
    main()
