"""Helpers of scripts/bench-solvers.sh: run a command and time it, read a
bake directory's manifest and tables (OpenEXR read with the standard library
only: scanline float32, NONE, ZIPS or ZIP, what skinbake writes), compare
two tables.  usage: python3 bench_tables.py COMMAND ARGS..."""
import json, math, resource, struct, subprocess, sys, time, zlib


def read_exr(path):
    """{channel: rows} of a scanline float32 OpenEXR file."""
    b = open(path, 'rb').read()
    assert b[:4] == b'\x76\x2f\x31\x01', path + ': not an OpenEXR file'
    p, attrs = 8, {}
    while b[p] != 0:
        e = b.index(b'\0', p); name = b[p:e].decode(); p = e + 1
        e = b.index(b'\0', p); typ = b[p:e].decode(); p = e + 1
        (n,) = struct.unpack_from('<i', b, p); p += 4
        attrs[name] = (typ, b[p:p + n]); p += n
    p += 1
    ch, q, v = [], 0, attrs['channels'][1]
    while v[q] != 0:
        e = v.index(b'\0', q)
        ch.append((v[q:e].decode(), struct.unpack_from('<i', v, e + 1)[0]))
        q = e + 17
    x0, y0, x1, y1 = struct.unpack('<4i', attrs['dataWindow'][1])
    w, h, comp = x1 - x0 + 1, y1 - y0 + 1, attrs['compression'][1][0]
    lpc = {0: 1, 2: 1, 3: 16}[comp]
    offs = struct.unpack_from('<%dQ' % ((h + lpc - 1) // lpc), b, p)
    out = {c: [None] * h for c, _ in ch}
    for o in offs:
        y, n = struct.unpack_from('<ii', b, o)
        d = b[o + 8:o + 8 + n]
        lines = min(lpc, y1 + 1 - y)
        if comp and n < lines * w * 4 * len(ch):
            t = bytearray(zlib.decompress(d))
            for i in range(1, len(t)):
                t[i] = (t[i - 1] + t[i] - 128) & 0xff
            half = (len(t) + 1) // 2
            u = bytearray(len(t)); u[0::2] = t[:half]; u[1::2] = t[half:]
            d = bytes(u)
        q = 0
        for r in range(lines):
            for c, typ in ch:
                assert typ == 2, 'float32 channels only'
                out[c][y - y0 + r] = struct.unpack_from('<%df' % w, d, q); q += 4 * w
    return out


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


main()
