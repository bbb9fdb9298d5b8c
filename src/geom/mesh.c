/* mesh: read triangle meshes from model files through libassimp's C API and
 * flatten the file's node hierarchy into one vertex and triangle list. */
#include "config.h"

#include "geom/mesh.h"

#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <dlfcn.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/util.h"

/* libassimp is loaded when the first model is read, not with the program:
 * with its C++ runtime and codecs it was 3 of the 9 ms every command spent
 * starting up (dynamic loading and relocations), and only scenes with
 * meshes use it.  ASSIMP_SONAME comes from configure. */
static struct {
	__typeof__(aiImportFile) *ImportFile;
	__typeof__(aiReleaseImport) *ReleaseImport;
	__typeof__(aiGetErrorString) *GetErrorString;
	__typeof__(aiIsExtensionSupported) *IsExtensionSupported;
	__typeof__(aiGetExtensionList) *GetExtensionList;
	__typeof__(aiGetMaterialColor) *GetMaterialColor;
	__typeof__(aiGetMaterialFloatArray) *GetMaterialFloatArray;
	__typeof__(aiGetMaterialTexture) *GetMaterialTexture;
	__typeof__(aiIdentityMatrix4) *IdentityMatrix4;
	__typeof__(aiMultiplyMatrix4) *MultiplyMatrix4;
	char *error;		/* why loading failed, else NULL */
} ai;
static pthread_once_t ai_once = PTHREAD_ONCE_INIT;

static void ai_load(void)
{
	void *h = dlopen(ASSIMP_SONAME, RTLD_NOW | RTLD_LOCAL);
	if (h == NULL) {
		const char *e = dlerror();
		ai.error = xasprintf("cannot load libassimp (%s): %s", ASSIMP_SONAME,
		    e ? e : "dlopen failed");
		return;
	}
	struct {
		const char *name;
		void **fn;
	} sym[] = {
		{ "aiImportFile", (void **)&ai.ImportFile },
		{ "aiReleaseImport", (void **)&ai.ReleaseImport },
		{ "aiGetErrorString", (void **)&ai.GetErrorString },
		{ "aiIsExtensionSupported", (void **)&ai.IsExtensionSupported },
		{ "aiGetExtensionList", (void **)&ai.GetExtensionList },
		{ "aiGetMaterialColor", (void **)&ai.GetMaterialColor },
		{ "aiGetMaterialFloatArray", (void **)&ai.GetMaterialFloatArray },
		{ "aiGetMaterialTexture", (void **)&ai.GetMaterialTexture },
		{ "aiIdentityMatrix4", (void **)&ai.IdentityMatrix4 },
		{ "aiMultiplyMatrix4", (void **)&ai.MultiplyMatrix4 },
	};
	for (size_t i = 0; i < sizeof sym / sizeof sym[0]; i++)
		if ((*sym[i].fn = dlsym(h, sym[i].name)) == NULL) {
			ai.error = xasprintf("libassimp (%s) lacks %s", ASSIMP_SONAME, sym[i].name);
			return;
		}
}

/* Triangulate polygons, share identical vertices, make smooth normals where
 * the file has none and tangents from the UVs where it has none (libassimp
 * keeps the file's own), and put points and lines into meshes of their own
 * (skipped below). */
#define IMPORT_FLAGS \
	(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals \
	    | aiProcess_CalcTangentSpace | aiProcess_SortByPType)

struct flat {
	struct mesh *m;
	const struct aiScene *sc;
	const char *path;
	const char *name;
	int cap_v, cap_t;
	int missing_uv;		/* a selected mesh has no UVs */
	int matched;		/* meshes taken */
};

static void apply(const struct aiMatrix4x4 *t, const struct aiVector3D *v, int point, double out[3])
{
	double w = point ? 1.0 : 0.0;
	out[0] = t->a1 * v->x + t->a2 * v->y + t->a3 * v->z + t->a4 * w;
	out[1] = t->b1 * v->x + t->b2 * v->y + t->b3 * v->z + t->b4 * w;
	out[2] = t->c1 * v->x + t->c2 * v->y + t->c3 * v->z + t->c4 * w;
}

static double normalize(double v[3])
{
	double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
	if (n > 0 && isfinite(n))
		for (int i = 0; i < 3; i++)
			v[i] /= n;
	return n;
}

static void cross(const double a[3], const double b[3], double out[3])
{
	out[0] = a[1] * b[2] - a[2] * b[1];
	out[1] = a[2] * b[0] - a[0] * b[2];
	out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Any unit vector orthogonal to n (for vertices whose UVs give no tangent). */
static void any_tangent(const double n[3], double t[3])
{
	double a[3] = { fabs(n[0]) < 0.9 ? 1 : 0, fabs(n[0]) < 0.9 ? 0 : 1, 0 };
	double d = a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
	for (int i = 0; i < 3; i++)
		t[i] = a[i] - d * n[i];
	normalize(t);
}

/* The diffuse colour and texture and the specular of material mat. */
static void read_material(struct flat *f, const struct aiMaterial *mat)
{
	struct mesh *m = f->m;
	struct aiColor4D c;
	struct aiString p;
	float shin;
	if (ai.GetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &c) == AI_SUCCESS) {
		m->diffuse_rgb[0] = c.r;
		m->diffuse_rgb[1] = c.g;
		m->diffuse_rgb[2] = c.b;
	}
	if (ai.GetMaterialColor(mat, AI_MATKEY_COLOR_SPECULAR, &c) == AI_SUCCESS)
		m->specular = (c.r + c.g + c.b) / 3;
	unsigned int one = 1;
	if (ai.GetMaterialFloatArray(mat, AI_MATKEY_SHININESS, &shin, &one) == AI_SUCCESS)
		m->shininess = shin;
	if (ai.GetMaterialTexture(mat, aiTextureType_DIFFUSE, 0, &p, NULL, NULL, NULL, NULL, NULL,
	    NULL) != AI_SUCCESS)
		return;
	/* Embedded ("*N" or a name the file carries inside, as in .zae). */
	for (unsigned i = 0; i < f->sc->mNumTextures; i++) {
		const struct aiTexture *t = f->sc->mTextures[i];
		int idx = p.data[0] == '*' ? atoi(p.data + 1) : -1;
		if ((idx == (int)i || !strcmp(t->mFilename.data, p.data)) && t->mHeight == 0) {
			m->texture_size = t->mWidth;
			m->texture = xmalloc(m->texture_size);
			memcpy(m->texture, t->pcData, m->texture_size);
			snprintf(m->texture_type, sizeof m->texture_type, "%.7s", t->achFormatHint);
			return;
		}
	}
	if (p.data[0] == '*')
		return;
	const char *slash = strrchr(f->path, '/'), *dot = strrchr(p.data, '.');
	if (p.data[0] == '/' || slash == NULL)
		m->texture_file = xstrdup(p.data);
	else
		m->texture_file = xasprintf("%.*s/%s", (int)(slash - f->path), f->path, p.data);
	snprintf(m->texture_type, sizeof m->texture_type, "%.7s", dot ? dot + 1 : "");
}

/* libassimp's computed bitangents changed handedness in 5.3 and 5.4 (Debian
 * 13: -dP/dv; 5.2 and 6.0: +dP/dv; assimp pull requests 4397 and 5542).  So
 * the handedness taken from them (tangent[v][3]) is checked against the UVs
 * of the mesh's triangles (dP/dv, signed by the UV winding, area-weighted
 * per vertex) and flipped for the whole mesh when most vertices disagree.
 * A file's own consistent tangents agree and are kept. */
static void check_handedness(struct mesh *m, int v0, int nv, int t0)
{
	double *acc = xcalloc((size_t)nv, sizeof *acc);
	for (int t = t0; t < m->n_triangles; t++) {
		const int *tri = m->triangle[t];
		double e1[3], e2[3], dpdv[3];
		double du1 = m->uv[tri[1]][0] - m->uv[tri[0]][0];
		double dv1 = m->uv[tri[1]][1] - m->uv[tri[0]][1];
		double du2 = m->uv[tri[2]][0] - m->uv[tri[0]][0];
		double dv2 = m->uv[tri[2]][1] - m->uv[tri[0]][1];
		double det = du1 * dv2 - du2 * dv1;
		if (det == 0)
			continue;
		for (int i = 0; i < 3; i++) {
			e1[i] = m->position[tri[1]][i] - m->position[tri[0]][i];
			e2[i] = m->position[tri[2]][i] - m->position[tri[0]][i];
			dpdv[i] = (du1 * e2[i] - du2 * e1[i]) * (det > 0 ? 1 : -1);
		}
		for (int j = 0; j < 3; j++) {
			double nb[3];
			cross(m->normal[tri[j]], m->tangent[tri[j]], nb);
			acc[tri[j] - v0] += nb[0] * dpdv[0] + nb[1] * dpdv[1] + nb[2] * dpdv[2];
		}
	}
	int agree = 0;
	int disagree = 0;
	for (int k = 0; k < nv; k++) {
		if (acc[k] == 0)
			continue;
		if ((acc[k] > 0) == (m->tangent[v0 + k][3] > 0))
			agree++;
		else
			disagree++;
	}
	if (disagree > agree)
		for (int k = 0; k < nv; k++)
			m->tangent[v0 + k][3] = -m->tangent[v0 + k][3];
	free(acc);
}

/* Append mesh am under node transform t (normals through the inverse
 * transpose: the cofactor matrix, normalised). */
static void append(struct flat *f, const struct aiMesh *am, const struct aiMatrix4x4 *t)
{
	struct mesh *m = f->m;
	int nv = (int)am->mNumVertices, nt = 0;
	for (unsigned i = 0; i < am->mNumFaces; i++)
		nt += am->mFaces[i].mNumIndices == 3;
	if (nt == 0)
		return;
	if (f->matched++ == 0)
		read_material(f, f->sc->mMaterials[am->mMaterialIndex]);
	if (am->mTextureCoords[0] == NULL)
		f->missing_uv = 1;
	if (m->n_vertices + nv > f->cap_v) {
		f->cap_v = 2 * (m->n_vertices + nv);
		m->position = xreallocarray(m->position, (size_t)f->cap_v, sizeof *m->position);
		m->normal = xreallocarray(m->normal, (size_t)f->cap_v, sizeof *m->normal);
		m->uv = xreallocarray(m->uv, (size_t)f->cap_v, sizeof *m->uv);
		m->tangent = xreallocarray(m->tangent, (size_t)f->cap_v, sizeof *m->tangent);
	}
	if (m->n_triangles + nt > f->cap_t) {
		f->cap_t = 2 * (m->n_triangles + nt);
		m->triangle = xreallocarray(m->triangle, (size_t)f->cap_t, sizeof *m->triangle);
	}
	int t0 = m->n_triangles;
	/* Cofactors of the upper 3x3: the inverse transpose up to a positive
	 * factor when det > 0; a mirroring node (det < 0) flips them back. */
	double a[3][3] = {
		{ t->a1, t->a2, t->a3 },
		{ t->b1, t->b2, t->b3 },
		{ t->c1, t->c2, t->c3 },
	};
	double c[3][3];
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			c[i][j] = a[(i + 1) % 3][(j + 1) % 3] * a[(i + 2) % 3][(j + 2) % 3]
			    - a[(i + 1) % 3][(j + 2) % 3] * a[(i + 2) % 3][(j + 1) % 3];
	double det = a[0][0] * c[0][0] + a[0][1] * c[0][1] + a[0][2] * c[0][2];
	double sgn = det < 0 ? -1 : 1;
	for (int k = 0; k < nv; k++) {
		int v = m->n_vertices + k;
		apply(t, &am->mVertices[k], 1, m->position[v]);
		const struct aiVector3D *n = am->mNormals ? &am->mNormals[k]
		    : &(struct aiVector3D){ 0, 0, 0 };
		for (int i = 0; i < 3; i++)
			m->normal[v][i] = sgn * (c[i][0] * n->x + c[i][1] * n->y + c[i][2] * n->z);
		if (normalize(m->normal[v]) == 0 || !isfinite(m->normal[v][0])) {
			m->normal[v][0] = 0;
			m->normal[v][1] = 0;
			m->normal[v][2] = 1;
		}
		if (am->mTextureCoords[0] == NULL) {
			m->uv[v][0] = m->uv[v][1] = 0;
			any_tangent(m->normal[v], m->tangent[v]);
			m->tangent[v][3] = 1;
			continue;
		}
		m->uv[v][0] = am->mTextureCoords[0][k].x;
		m->uv[v][1] = am->mTextureCoords[0][k].y;
		double tg[3] = { 0, 0, 0 }, bt[3] = { 0, 0, 0 }, nb[3];
		if (am->mTangents != NULL && am->mBitangents != NULL) {
			apply(t, &am->mTangents[k], 0, tg);
			apply(t, &am->mBitangents[k], 0, bt);
		}
		/* Gram-Schmidt against the normal; degenerate UVs get any tangent. */
		const double *nrm = m->normal[v];
		double d = tg[0] * nrm[0] + tg[1] * nrm[1] + tg[2] * nrm[2];
		for (int i = 0; i < 3; i++)
			tg[i] -= d * m->normal[v][i];
		if (!(normalize(tg) > 1e-12) || !isfinite(tg[0]))
			any_tangent(m->normal[v], tg);
		cross(m->normal[v], tg, nb);
		memcpy(m->tangent[v], tg, sizeof tg);
		m->tangent[v][3] = nb[0] * bt[0] + nb[1] * bt[1] + nb[2] * bt[2] < 0 ? -1 : 1;
	}
	for (unsigned i = 0; i < am->mNumFaces; i++) {
		const struct aiFace *fc = &am->mFaces[i];
		if (fc->mNumIndices != 3)
			continue;
		int *tri = m->triangle[m->n_triangles++];
		for (int j = 0; j < 3; j++)
			tri[j] = m->n_vertices + (int)fc->mIndices[sgn < 0 ? 2 - j : j];
	}
	if (am->mTextureCoords[0] != NULL)
		check_handedness(m, m->n_vertices, nv, t0);
	m->n_vertices += nv;
}

static int name_is(const struct aiString *s, const char *name)
{
	return name != NULL && !strcmp(s->data, name);
}

static void walk(struct flat *f, const struct aiScene *sc, const struct aiNode *node,
    const struct aiMatrix4x4 *parent, int node_selected)
{
	struct aiMatrix4x4 t = *parent;
	ai.MultiplyMatrix4(&t, &node->mTransformation);
	int sel = node_selected || name_is(&node->mName, f->name);
	for (unsigned i = 0; i < node->mNumMeshes; i++) {
		const struct aiMesh *am = sc->mMeshes[node->mMeshes[i]];
		if (f->name == NULL || sel || name_is(&am->mName, f->name))
			append(f, am, &t);
	}
	for (unsigned i = 0; i < node->mNumChildren; i++)
		walk(f, sc, node->mChildren[i], &t, sel);
}

/* "a, b, c": the mesh names of the file and the names of nodes holding meshes. */
static char *names(const struct aiScene *sc)
{
	char *s = xstrdup("");
	for (unsigned i = 0; i < sc->mNumMeshes; i++) {
		char *t = xasprintf("%s%s'%s'", s, *s ? ", " : "", sc->mMeshes[i]->mName.data);
		free(s);
		s = t;
	}
	return s;
}

static char *format_error(const char *path)
{
	const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
	if (dot != NULL && (slash == NULL || dot > slash) && !ai.IsExtensionSupported(dot)) {
		struct aiString ext = { 0 };	/* appended to: start empty */
		ai.GetExtensionList(&ext);
		return xasprintf("%s: unknown model format '%s' (libassimp reads %s)", path, dot,
		    ext.data);
	}
	return xasprintf("%s: not a model libassimp can read: %s", path, ai.GetErrorString());
}

/* Vertices a renderer can take: finite, and far below float's 3.4e38
 * (POV-Ray's limit for coordinates is about 1e7 scene units; 1e30 leaves
 * room and still refuses the overflowed 1e39 -> inf of a text file). */
#define MESH_MAX_COORD 1e30

static int check_vertices(const struct mesh *m, const char *path, char **cause)
{
	for (int v = 0; v < m->n_vertices; v++)
		for (int i = 0; i < 3; i++)
			if (!isfinite(m->position[v][i]) ||
			    fabs(m->position[v][i]) > MESH_MAX_COORD) {
				*cause = xasprintf("%s: vertex %d has %c = %g; mesh coordinates "
				    "must be finite and within [-%g, %g]", path, v, "xyz"[i],
				    m->position[v][i], MESH_MAX_COORD, MESH_MAX_COORD);
				return -1;
			}
	return 0;
}

struct mesh *mesh_load(const char *path, const char *name, char **cause)
{
	struct stat st;
	if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
		*cause = xasprintf("%s is a directory, not a model file", path);
		return NULL;
	}
	FILE *fp = fopen(path, "rb");
	if (fp == NULL) {
		*cause = xasprintf("%s: %s", path, strerror(errno));
		return NULL;
	}
	fclose(fp);
	pthread_once(&ai_once, ai_load);
	if (ai.error) {
		*cause = xasprintf("%s: %s", path, ai.error);
		return NULL;
	}
	const struct aiScene *sc = ai.ImportFile(path, IMPORT_FLAGS);
	if (sc == NULL || sc->mRootNode == NULL) {
		*cause = format_error(path);
		if (sc != NULL)
			ai.ReleaseImport(sc);
		return NULL;
	}
	struct mesh *m = xcalloc(1, sizeof *m);
	struct flat f = { .m = m, .sc = sc, .path = path, .name = name };
	m->diffuse_rgb[0] = m->diffuse_rgb[1] = m->diffuse_rgb[2] = 0.8;
	struct aiMatrix4x4 id;
	ai.IdentityMatrix4(&id);
	walk(&f, sc, sc->mRootNode, &id, 0);
	if (m->n_triangles == 0) {
		char *list = names(sc);
		if (name != NULL)
			*cause = xasprintf("%s: no mesh '%s' with triangles (the file has %s)",
			    path, name, *list ? list : "no meshes");
		else
			*cause = xasprintf("%s: no triangles in the file", path);
		free(list);
		ai.ReleaseImport(sc);
		mesh_free(m);
		return NULL;
	}
	if (check_vertices(m, path, cause) != 0) {
		ai.ReleaseImport(sc);
		mesh_free(m);
		return NULL;
	}
	if (f.missing_uv) {
		free(m->uv);
		free(m->tangent);
		m->uv = NULL;
		m->tangent = NULL;
	}
	m->source = name ? xasprintf("%s: %s", path, name) : xstrdup(path);
	ai.ReleaseImport(sc);
	return m;
}

void mesh_free(struct mesh *m)
{
	if (m == NULL)
		return;
	free(m->source);
	free(m->position);
	free(m->normal);
	free(m->uv);
	free(m->tangent);
	free(m->triangle);
	free(m->texture_file);
	free(m->texture);
	free(m);
}

void mesh_bounds(const struct mesh *m, double lo[3], double hi[3])
{
	for (int i = 0; i < 3; i++) {
		lo[i] = INFINITY;
		hi[i] = -INFINITY;
	}
	for (int v = 0; v < m->n_vertices; v++)
		for (int i = 0; i < 3; i++) {
			lo[i] = fmin(lo[i], m->position[v][i]);
			hi[i] = fmax(hi[i], m->position[v][i]);
		}
}

double mesh_area(const struct mesh *m)
{
	double a = 0;
	for (int k = 0; k < m->n_triangles; k++) {
		const double *p0 = m->position[m->triangle[k][0]];
		const double *p1 = m->position[m->triangle[k][1]];
		const double *p2 = m->position[m->triangle[k][2]];
		double e1[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
		double e2[3] = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };
		double c[3];
		cross(e1, e2, c);
		a += 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
	}
	return a;
}

double mesh_uv_area(const struct mesh *m)
{
	double a = 0;
	if (m->uv == NULL)
		return 0;
	for (int k = 0; k < m->n_triangles; k++) {
		const double *a0 = m->uv[m->triangle[k][0]];
		const double *a1 = m->uv[m->triangle[k][1]];
		const double *a2 = m->uv[m->triangle[k][2]];
		double cr = (a1[0] - a0[0]) * (a2[1] - a0[1]) - (a2[0] - a0[0]) * (a1[1] - a0[1]);
		a += 0.5 * fabs(cr);
	}
	return a;
}

/* The new vertex on edge (a, b): PN-triangle edge midpoint
 * (pa + pb) / 2 - (wab na + wba nb) / 8 with wab = (pb - pa) . na. */
static void edge_vertex(struct mesh *m, int a, int b, int v)
{
	const double *pa = m->position[a], *pb = m->position[b];
	const double *na = m->normal[a], *nb = m->normal[b];
	double d[3] = { pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2] };
	double wab = d[0] * na[0] + d[1] * na[1] + d[2] * na[2];
	double wba = -(d[0] * nb[0] + d[1] * nb[1] + d[2] * nb[2]);
	for (int i = 0; i < 3; i++) {
		m->position[v][i] = 0.5 * (pa[i] + pb[i]) - (wab * na[i] + wba * nb[i]) / 8;
		m->normal[v][i] = na[i] + nb[i];
	}
	if (normalize(m->normal[v]) == 0)
		memcpy(m->normal[v], na, sizeof m->normal[v]);
	if (m->uv == NULL)
		return;
	double t[3];
	for (int i = 0; i < 2; i++)
		m->uv[v][i] = 0.5 * (m->uv[a][i] + m->uv[b][i]);
	for (int i = 0; i < 3; i++)
		t[i] = m->tangent[a][i] + m->tangent[b][i];
	double dn = t[0] * m->normal[v][0] + t[1] * m->normal[v][1] + t[2] * m->normal[v][2];
	for (int i = 0; i < 3; i++)
		t[i] -= dn * m->normal[v][i];
	if (!(normalize(t) > 1e-12))
		any_tangent(m->normal[v], t);
	memcpy(m->tangent[v], t, sizeof t);
	m->tangent[v][3] = m->tangent[a][3];
}

struct edge_key {
	int a, b, v;	/* a < b; v the new vertex */
};

static int edge_cmp(const void *x, const void *y)
{
	const struct edge_key *p = x, *q = y;
	return p->a != q->a ? (p->a > q->a) - (p->a < q->a) : (p->b > q->b) - (p->b < q->b);
}

void mesh_subdivide(struct mesh *m)
{
	int nt = m->n_triangles, nv = m->n_vertices;
	struct edge_key *e = xmalloc(sizeof *e * 3 * (size_t)nt);
	for (int t = 0; t < nt; t++)
		for (int j = 0; j < 3; j++) {
			int a = m->triangle[t][j], b = m->triangle[t][(j + 1) % 3];
			e[3 * t + j] = (struct edge_key){ a < b ? a : b, a < b ? b : a, -1 };
		}
	qsort(e, 3 * (size_t)nt, sizeof *e, edge_cmp);
	int ne = 0;
	for (int i = 0; i < 3 * nt; i++)
		if (ne == 0 || edge_cmp(&e[ne - 1], &e[i]) != 0)
			e[ne++] = e[i];
	size_t cap = (size_t)(nv + ne);
	m->position = xreallocarray(m->position, cap, sizeof *m->position);
	m->normal = xreallocarray(m->normal, cap, sizeof *m->normal);
	if (m->uv != NULL) {
		m->uv = xreallocarray(m->uv, cap, sizeof *m->uv);
		m->tangent = xreallocarray(m->tangent, cap, sizeof *m->tangent);
	}
	for (int i = 0; i < ne; i++) {
		e[i].v = nv + i;
		edge_vertex(m, e[i].a, e[i].b, e[i].v);
	}
	int (*tri)[3] = xmalloc(sizeof *tri * 4 * (size_t)nt);
	for (int t = 0; t < nt; t++) {
		int c[3], mid[3];
		for (int j = 0; j < 3; j++) {
			int a = m->triangle[t][j], b = m->triangle[t][(j + 1) % 3];
			struct edge_key k = { a < b ? a : b, a < b ? b : a, -1 };
			mid[j] =
			    ((struct edge_key *)bsearch(&k, e, (size_t)ne, sizeof *e, edge_cmp))->v;
			c[j] = a;
		}
		/* Corners keep the winding: (c0, m01, m20), (m01, c1, m12), ... */
		int q[4][3] = {
			{ c[0], mid[0], mid[2] },
			{ mid[0], c[1], mid[1] },
			{ mid[2], mid[1], c[2] },
			{ mid[0], mid[1], mid[2] },
		};
		memcpy(tri[4 * t], q, sizeof q);
	}
	free(m->triangle);
	m->triangle = tri;
	m->n_triangles = 4 * nt;
	m->n_vertices = nv + ne;
	free(e);
}
