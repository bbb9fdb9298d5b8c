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

/* The same file a band of rows at a time (maps fit): rows in order, each
 * nrows of planes[c] (w floats per row); the writer buffers up to one
 * chunk (16 rows).  A failing call returns -1 (NULL) and *cause, removes
 * the temporary file and frees wr. */
struct exrio_writer;
struct exrio_writer *exrio_writer_open(const char *path, int w, int h, int nch,
    const char *const *names,
    int nattr, const struct exr_attr_kv *attrs, char **cause);
int exrio_writer_rows(struct exrio_writer *wr, const float *const *planes, int nrows, char **cause);
/* After the last row: finish and rename into place; frees wr. */
int exrio_writer_close(struct exrio_writer *wr, char **cause);
void exrio_writer_abort(struct exrio_writer *wr);	/* NULL is a no-op */

/* Size of PATH's data window; -1 and *cause on failure. */
int exrio_size(const char *path, int *w, int *h, char **cause);
/* Read channel NAME of PATH into out (w*h floats, size must match). */
int exrio_read_channel(const char *path, const char *name, int w, int h, float *out, char **cause);
/* Rows y0 .. y0 + ny - 1 of channel NAME into out (ny*w floats). */
int exrio_read_channel_rows(const char *path, const char *name, int w, int h, int y0, int ny,
    float *out,
    char **cause);
/* A string attribute of PATH (caller frees), or NULL with *cause. */
char *exrio_read_string_attr(const char *path, const char *key, char **cause);
#endif
