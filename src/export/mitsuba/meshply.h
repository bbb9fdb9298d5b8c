/* meshply: a placed scene mesh as a binary PLY file for Mitsuba 3, and the
 * test that it closes a volume (what the volumetric layers need). */
#ifndef SKINBAKE_MESHPLY_H
#define SKINBAKE_MESHPLY_H
struct mesh;

/* Write M (scene world coordinates, POV-Ray's left-handed frame) to PATH as
 * binary little-endian PLY in Mitsuba's right-handed frame, (x, y, z) ->
 * (x, y, -z) for positions and normals (the mirror turns the frame, so the
 * triangles keep their order), with vertex normals and, when M has them,
 * UVs.  All or nothing; -1 and *cause on failure. */
int meshply_write(const struct mesh *m, const char *path, char **cause);

/* Edges of M not shared by exactly two triangles once vertices at equal
 * positions are one (split UV seams are no holes): 0 for a closed surface. */
long meshply_open_edges(const struct mesh *m);
#endif
