"""Helpers of scripts/bench-solvers.sh and scripts/bench-bake.sh: run a
command and time it, read a bake directory's manifest and tables (OpenEXR by
tests/lib/images.py, the standard library only), compare two tables.
usage: python3 bench_tables.py COMMAND ARGS..."""
import json, math, os, resource, subprocess, sys, time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "lib"))
from images import read_exr  # noqa: E402


def manifest(d):
    return json.load(open(d + '/manifest.json'))


def table(d):
    """Values, errors and solid-angle weights of every bin of every entry."""
    m, t = manifest(d), read_exr(d + '/brdf.exr')
    edges = [math.radians(x) for x in m['theta_o_edges_deg']]
    n_to = len(edges) - 1
    f, e, w = [], [], []
    for wl in m['wavelengths_nm']:
        a, b = t['fr.%dnm' % wl], t['fr_err.%dnm' % wl]
        for row in range(len(a)):
            it = row % n_to
            om = math.cos(edges[it]) - math.cos(edges[it + 1])
            f += a[row]; e += b[row]; w += [om] * len(a[row])
    return f, e, w


def main():
    cmd = sys.argv[1]
    if cmd == 'run':	# run LOG CMD...: "wall cpu" seconds of CMD
        r0, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.monotonic()
        with open(sys.argv[2], 'w') as log:
            rc = subprocess.call(sys.argv[3:], stdout=log, stderr=subprocess.STDOUT)
        t1, r1 = time.monotonic(), resource.getrusage(resource.RUSAGE_CHILDREN)
        if rc != 0:
            sys.stderr.write(open(sys.argv[2]).read())
            sys.exit(rc)
        print('%.3f %.3f' % (t1 - t0, r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime))
    elif cmd == 'info':	# info DIR: photons (pilot included), table seconds, RMS error, radial seconds, solver
        m = manifest(sys.argv[2]); r = m['result']
        print(r['photons'] + r.get('pilot_photons', 0), '%.3f' % r['seconds'], '%.4g' % r['rms_rel_err'],
              '%.3f' % m['radial'].get('seconds', 0.0), m.get('solver', {}).get('name', 'mc'))
    elif cmd == 'quad':	# quad DIR: range of quadrature nodes and Fourier orders over the entries
        j = manifest(sys.argv[2])['jobs']
        q = [x.get('n_quad', 0) for x in j]; o = [x.get('fourier_orders', 0) for x in j]
        print('%d-%d %d-%d' % (min(q), max(q), min(o), max(o)))
    elif cmd == 'cmp':	# cmp DIR REF: actual RMS relative difference to REF, DIR's own reported RMS error
        f, e, w = table(sys.argv[2])
        g, _, _ = table(sys.argv[3])
        keep = [i for i in range(len(g)) if g[i] > 0]
        sw = sum(w[i] for i in keep)
        d = math.sqrt(sum(w[i] * ((f[i] - g[i]) / g[i]) ** 2 for i in keep) / sw)
        own = math.sqrt(sum(w[i] * ((e[i] / f[i]) if f[i] > 0 else 1.0) ** 2 for i in keep) / sw)
        print('%.4g %.4g' % (d, own))
    elif cmd == 'radius':	# radius DIR...: per wavelength the mean radius's spread over the bakes and their mean error
        rs = [manifest(d)['radial'] for d in sys.argv[2:]]
        wl = manifest(sys.argv[2])['wavelengths_nm']
        for k, x in enumerate(wl):
            v = [r['mean_radius_cm'][k] for r in rs]; e = [r['mean_radius_err_cm'][k] for r in rs]
            mu = sum(v) / len(v); sd = math.sqrt(sum((y - mu) ** 2 for y in v) / (len(v) - 1))
            print('%g %.5g %.3g %.3g' % (x, mu, sd / mu, sum(e) / len(e) / mu))
    else:
        sys.exit('unknown command ' + cmd)


if __name__ == "__main__":
    main()
