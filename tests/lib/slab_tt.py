"""Simulated transmittance of a bake's layer stack cut to a slab of D_MM millimetres (the
deeper layers shortened, the last one extended to fill): skinbake simulate --solver ad per
wavelength, weighted into linear sRGB by the manifest's rgb_from_wl.  For the back-light
checks of the translucent tests (pov_translucent.sh, blender_translucent.sh).

    sys.path.insert(0, os.path.join(os.environ["top_srcdir"], "tests", "lib"))
    from slab_tt import slab_tt_rgb
"""
import re
import subprocess


def slab_tt_rgb(skinbake, manifest, d_mm):
    """[Tt_R, Tt_G, Tt_B] of the stack of MANIFEST (a bake's parsed manifest.json) d_mm thick."""
    tt = []
    for lw in manifest["layers"]:
        layers, left = [], d_mm / 10
        for l in lw["layers"]:
            d = min(1e9 if l["d_cm"] == "inf" else l["d_cm"], left)
            if d <= 0:
                break
            layers.append(dict(l, d_cm=d))
            left -= d
        layers[-1]["d_cm"] += max(left, 0.0)
        args = []
        for l in reversed(layers):
            args += ["--layer", "d=%.6g,n=%g,mua=%g,mus=%g,g=%g" % (l["d_cm"], l["n"], l["mua_per_cm"],
                                                                  l["mus_per_cm"], l["g"])]
        out = subprocess.run([skinbake, "simulate", "--solver", "ad", "--ad-tol", "1e-3"] + args,
                             capture_output=True, text=True, check=True).stdout
        tt.append(float(re.search(r"^\s*Tt\s+(\S+)", out, re.M).group(1)))
    w = manifest["rgb"]["rgb_from_wl"]
    return [sum(w[c][k] * tt[k] for k in range(len(tt))) for c in range(3)]
