"""Write a closed slab mesh (OBJ): x, y in [-W, W] mm, front face z = 0 (normal -z), back face
z = D (normal +z), both as N x N grids of quads, the four sides one quad each; face normals.
usage: slab_obj.py D_MM W_MM N OUT.obj"""
import sys

d, w, n, out = float(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
v, vn, f = [], [], []


def quad(p, nrm):
    """A quad p[0..3] counter-clockwise seen from nrm's side."""
    vn.append(nrm)
    k = len(v)
    v.extend(p)
    ni = len(vn)
    f.append((k + 1, k + 2, k + 3, ni))
    f.append((k + 1, k + 3, k + 4, ni))


for i in range(n):
    for j in range(n):
        x0, x1 = -w + 2 * w * i / n, -w + 2 * w * (i + 1) / n
        y0, y1 = -w + 2 * w * j / n, -w + 2 * w * (j + 1) / n
        quad([(x0, y0, 0), (x0, y1, 0), (x1, y1, 0), (x1, y0, 0)], (0, 0, -1))
        quad([(x0, y0, d), (x1, y0, d), (x1, y1, d), (x0, y1, d)], (0, 0, 1))
quad([(-w, -w, 0), (w, -w, 0), (w, -w, d), (-w, -w, d)], (0, -1, 0))
quad([(-w, w, 0), (-w, w, d), (w, w, d), (w, w, 0)], (0, 1, 0))
quad([(-w, -w, 0), (-w, -w, d), (-w, w, d), (-w, w, 0)], (-1, 0, 0))
quad([(w, -w, 0), (w, w, 0), (w, w, d), (w, -w, d)], (1, 0, 0))
with open(out, "w") as fp:
    fp.write("# slab %g mm thick, %g mm wide\n" % (d, 2 * w))
    for p in v:
        fp.write("v %g %g %g\n" % p)
    for p in vn:
        fp.write("vn %g %g %g\n" % p)
    for a, b, c, ni in f:
        fp.write("f %d//%d %d//%d %d//%d\n" % (a, ni, b, ni, c, ni))
