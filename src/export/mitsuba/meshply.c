/* meshply: PLY writer and closed-surface test (see meshply.h). */
#include "config.h"
#include "export/mitsuba/meshply.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "geom/mesh.h"

static void put_f32(FILE *fp, double v)
{
	float f = (float)v;
	unsigned char b[4];
	uint32_t u;
	memcpy(&u, &f, 4);
	for (int k = 0; k < 4; k++)
		b[k] = (unsigned char)(u >> (8 * k));
	fwrite(b, 1, 4, fp);
}

static void put_i32(FILE *fp, int v)
{
	uint32_t u = (uint32_t)v;
	unsigned char b[4];
	for (int k = 0; k < 4; k++)
		b[k] = (unsigned char)(u >> (8 * k));
	fwrite(b, 1, 4, fp);
}

int meshply_write(const struct mesh *m, const char *path, char **cause)
{
	struct outfile of;
	if (outfile_open(&of, path, cause) != 0)
		return -1;
	FILE *fp = of.fp;
	fprintf(fp, "ply\nformat binary_little_endian 1.0\ncomment skinbake export mitsuba: %s\n", m->source);
	fprintf(fp, "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n", m->n_vertices);
	fprintf(fp, "property float nx\nproperty float ny\nproperty float nz\n");
	if (m->uv)
		fprintf(fp, "property float u\nproperty float v\n");
	fprintf(fp, "element face %d\nproperty list uchar int vertex_indices\nend_header\n", m->n_triangles);
	for (int i = 0; i < m->n_vertices; i++) {
		put_f32(fp, m->position[i][0]);
		put_f32(fp, m->position[i][1]);
		put_f32(fp, -m->position[i][2]);
		put_f32(fp, m->normal[i][0]);
		put_f32(fp, m->normal[i][1]);
		put_f32(fp, -m->normal[i][2]);
		if (m->uv) {
			put_f32(fp, m->uv[i][0]);
			put_f32(fp, m->uv[i][1]);
		}
	}
	for (int t = 0; t < m->n_triangles; t++) {
		fputc(3, fp);
		for (int k = 0; k < 3; k++)
			put_i32(fp, m->triangle[t][k]);
	}
	if (ferror(fp)) {
		*cause = xasprintf("%s: write error", path);
		outfile_abort(&of);
		return -1;
	}
	return outfile_commit(&of, cause);
}

static const struct mesh *cmp_mesh;

static int cmp_pos(const void *a, const void *b)
{
	const double *p = cmp_mesh->position[*(const int *)a], *q = cmp_mesh->position[*(const int *)b];
	return memcmp(p, q, 3 * sizeof(double));
}

static int cmp_u64(const void *a, const void *b)
{
	uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
	return x < y ? -1 : x > y;
}

long meshply_open_edges(const struct mesh *m)
{
	/* one id per distinct position (byte-equal coordinates: seams are split copies) */
	int n = m->n_vertices;
	int *order = xmalloc((size_t)n * sizeof *order), *id = xmalloc((size_t)n * sizeof *id);
	for (int i = 0; i < n; i++)
		order[i] = i;
	cmp_mesh = m;
	qsort(order, (size_t)n, sizeof *order, cmp_pos);
	int next = -1;
	for (int i = 0; i < n; i++) {
		if (i == 0 || cmp_pos(&order[i - 1], &order[i]) != 0)
			next++;
		id[order[i]] = next;
	}
	size_t ne = (size_t)m->n_triangles * 3;
	uint64_t *edge = xmalloc(ne * sizeof *edge);
	size_t used = 0;
	for (int t = 0; t < m->n_triangles; t++)
		for (int k = 0; k < 3; k++) {
			uint64_t a = (uint64_t)id[m->triangle[t][k]], b = (uint64_t)id[m->triangle[t][(k + 1) % 3]];
			if (a != b)	/* a collapsed edge bounds nothing */
				edge[used++] = a < b ? (a << 32) | b : (b << 32) | a;
		}
	ne = used;
	qsort(edge, ne, sizeof *edge, cmp_u64);
	long open = 0;
	for (size_t i = 0; i < ne;) {
		size_t j = i;
		while (j < ne && edge[j] == edge[i])
			j++;
		if (j - i != 2)
			open++;
		i = j;
	}
	free(edge);
	free(id);
	free(order);
	return open;
}
