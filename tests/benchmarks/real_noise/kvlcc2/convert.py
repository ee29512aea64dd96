# Converts MARIN KVLCC2 free-running records (SIMMAN 2008) to CSV for vesselid.
# Columns of the .dat (inferred from ranges): t, x0, y0, phi[deg], psi[deg], xdot, ydot [m/s],
# p[deg/s], r[deg/s], delta[deg], n[rpm]; full-scale values, model sampled at 0.02 s
# (0.02*sqrt(45.7) = 0.1352 s full scale). The time column is printed with 3 significant digits,
# so time is rebuilt as i*dt. Downsampled by STEP.
import math, sys
import os
SRC = os.path.join(os.environ.get('VESSELID_KVLCC2_DIR', '../shared/data/kvlcc2/kvlcc2'), 'MARIN_FREE_KVLCC2_%s_m.dat')
DT = 0.02 * math.sqrt(45.7)
runs = {'zz_10': ('zz10', 4), 'zz_-10': ('zzm10', 4), 'zz_20': ('zz20', 4), 'zz_-20': ('zzm20', 4),
        'tc_35': ('tc35', 8), 'tc_-35': ('tcm35', 8)}
for src, (name, step) in runs.items():
    rows = [list(map(float, l.split())) for l in open(SRC % src).read().splitlines()[3:] if l.strip()]
    with open(name + '.csv', 'w') as f:
        f.write('t,delta,psi,r,speed\n')
        for i in range(0, len(rows), step):
            r = rows[i]
            f.write('%.4f,%.4g,%.4g,%.4g,%.4g\n' % (i * DT, r[9], r[4], r[8], math.hypot(r[5], r[6])))
    print(name, len(rows), '->', (len(rows) + step - 1) // step, 'rows, T', round((len(rows) - 1) * DT, 1))
