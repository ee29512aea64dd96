# Converts LSJohnsen/Otter-USV field logs (Maritime Robotics Otter, 2024-04-23, Oslofjord, path
# following) to CSV for vesselid: t [s], tauN (the controller's yaw-moment demand tau_N [N m] / 100),
# tauX/100, psi [deg, unwrapped from current_orientation_3], r [deg/s, current_rotational_velocities_3].
# dn2 = (n1|n1| - n2|n2|)/1e6 [rpm^2/1e6], the differential of the allocated propeller speeds.
# Rows without tau_N are dropped, and the first SKIP s (start-up spin) left out.
import csv, os, sys
SKIP = 10.0
runs = ['12-27-203', '12-44-083', '12-50-003', '12-55-233', '16-07-363fast2meterpersekundr55']
names = {'12-27-203': 'otter_1227', '12-44-083': 'otter_1244', '12-50-003': 'otter_1250',
         '12-55-233': 'otter_1255', '16-07-363fast2meterpersekundr55': 'otter_1607'}
for run in runs:
    rows = list(csv.DictReader(open(os.path.join(sys.argv[1] if len(sys.argv) > 1 else 'raw', '2024-04-23_%s.csv' % run)), delimiter=';'))
    out = []
    for r in rows:
        try:
            t = float(r['current_time']); tn = float(r['tau_N']); tx = float(r['tau_X']); n1 = float(r['n1']); n2 = float(r['n2'])
            psi = float(r['current_orientation_3']); rr = float(r['current_rotational_velocities_3'])
        except (ValueError, KeyError):
            continue
        out.append([t, tn, tx, psi, rr, (n1*abs(n1) - n2*abs(n2)) / 1e6])
    t0 = out[0][0]
    out = [o for o in out if o[0] - t0 >= SKIP]
    t0 = out[0][0]
    prev = None; off = 0.0
    with open(names[run] + '.csv', 'w') as f:
        f.write('t,tauN,tauX,psi,r,dn2\n')
        for t, tn, tx, psi, rr, dn in out:
            if prev is not None:
                d = psi - prev
                if d > 180: off -= 360
                elif d < -180: off += 360
            prev = psi
            f.write('%.3f,%.5g,%.5g,%.3f,%.3f,%.5g\n' % (t - t0, tn / 100, tx / 100, psi + off, rr, dn))
    print(names[run], len(out), 'rows, T %.1f s' % (out[-1][0] - t0))
