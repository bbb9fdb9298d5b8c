/* exrio: float32 scanline OpenEXR files with named channels and string
 * attributes, through the OpenEXRCore C API only (never the C++ Imf API).
 * Works around the OpenEXR 3.1.5 C-core bug that decodes a chunk whose
 * compressed size equals its raw size as garbage: such chunks are stored raw. */
#ifndef SKINBAKE_EXRIO_H
#define SKINBAKE_EXRIO_H

struct exr_attr_kv {
	const char *key;	/* attribute name, e.g. "skinbake:axes" */
	const char *value;	/* string value */
};

/* Write PATH (through a temporary file renamed into place): w x h pixels,
 * nch channels named names[c] with planes[c] row-major (row 0 at the top),
 * ZIP compression, plus nattr string attributes.  -1 and *cause on failure. */
int exrio_write(const char *path, int w, int h, int nch, const char *const *names,
    const float *const *planes, int nattr, const struct exr_attr_kv *attrs, char **cause);

/* Size of PATH's data window; -1 and *cause on failure. */
int exrio_size(const char *path, int *w, int *h, char **cause);
/* Read channel NAME of PATH into out (w*h floats, size must match). */
int exrio_read_channel(const char *path, const char *name, int w, int h, float *out, char **cause);
/* A string attribute of PATH (caller frees), or NULL with *cause. */
char *exrio_read_string_attr(const char *path, const char *key, char **cause);
#endif
