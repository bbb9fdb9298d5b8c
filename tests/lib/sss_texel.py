"""A texel's fitted closure (colour and length per channel, from a maps export) against the fit of
a single bake of that texel's parameters (tests/sss_fit_print), within the stated error: 3 sigma
of the two profiles' Monte Carlo error (the relative standard error of the power, from
radial.rd_r_err, for the colour, which sets the power; of the mean radius,
radial.mean_radius_err_cm, for the length, which sets it; the largest over the channel's
wavelengths, an upper bound for their weighted mean), plus the error of interpolating linearly in
the axis coordinate t between two nodes, bounded by (t - t0)(t1 - t)/2 times the members' second
divided difference.  Used by tests/maps_pov_translucent.sh and tests/maps_blender_translucent.sh."""
import json
import math


def rel_err(bake, kind, c):
    """Largest relative standard error over the wavelengths that make channel c."""
    m = json.load(open(bake + "/manifest.json"))
    w, rad = m["rgb"]["rgb_from_wl"][c], m["radial"]
    if kind == "length":
        e = [s / x for s, x in zip(rad["mean_radius_err_cm"], rad["mean_radius_cm"]) if x > 0]
    else:
        dr = rad["dr_cm"]
        ring = [2 * math.pi * (k + 0.5) * dr * dr for k in range(rad["n_r"])]
        e = [math.sqrt(sum((a * s) ** 2 for a, s in zip(ring, es)))
             / sum(a * x for a, x in zip(ring, xs)) for xs, es in zip(rad["rd_r"], rad["rd_r_err"])]
    return max(x for x, wj in zip(e, w) if abs(wj) > 0.05 * max(abs(y) for y in w))


def check(texel, direct, members, fam, v, member_bake, single_bake):
    """TEXEL {"colour": [R, G, B], "length_mm": [R, G, B]} at axis value V against DIRECT (the
    single bake's fit, same keys); MEMBERS the fits of the family's three nodes (one axis), FAM
    the family directory, MEMBER_BAKE and SINGLE_BAKE the bakes whose errors count.  Returns
    (all within, [description per quantity and channel])."""
    ax = json.load(open(fam + "/family.json"))["axes"][0]
    coord = math.log if ax["log_coordinate"] else float  # the axis coordinate t is linear in it
    ok, out = True, []
    for kind, key in (("colour", "colour"), ("length", "length_mm")):
        for c, ch in enumerate("RGB"):
            got, want = texel[key][c], direct[key][c]
            # Node values in the quantity the blend is linear in (the length: its log), and t.
            f = [m[key][c] if kind == "colour" else math.log(m[key][c]) for m in members]
            t, tv = [coord(x) for x in ax["nodes"]], coord(v)
            j = 0 if tv < t[1] else 1
            dd = ((f[2] - f[1]) / (t[2] - t[1]) - (f[1] - f[0]) / (t[1] - t[0])) / (t[2] - t[0]) * 2
            interp = abs((tv - t[j]) * (t[j + 1] - tv) / 2 * dd)
            if kind == "colour":
                interp /= abs(want)
            sig = math.hypot(rel_err(member_bake, kind, c), rel_err(single_bake, kind, c))
            tol = 3 * sig + interp
            dev = got / want - 1
            ok &= abs(dev) <= tol
            out.append("%s %s %+.2f%% (tol %.2f%%: 3 sigma %.2f%% + interpolation %.2f%%)"
                       % (kind, ch, 100 * dev, 100 * tol, 300 * sig, 100 * interp))
    return ok, out
