/* pngio: PNG files through libpng's classic API: 16-bit grayscale and RGB
 * for data maps (no gAMA/sRGB chunk, so importers take the values as data),
 * 8-bit RGB for previews (with an sRGB chunk), and tEXt metadata.  Files are
 * written through a temporary name and renamed into place. */
#ifndef SKINBAKE_PNGIO_H
#define SKINBAKE_PNGIO_H
#include <stdint.h>

struct png_text_kv {
	const char *key;	/* tEXt keyword, 1-79 Latin-1 characters */
	const char *value;
};

/* channels: 1 (gray), 3 (RGB) or 4 (RGBA); bits: 8 or 16.  px holds
 * w*h*channels samples, row 0 at the top; 8-bit data is passed in the low
 * byte of each uint16_t.  srgb marks an 8-bit colour preview as sRGB. */
int pngio_write(const char *path, int w, int h, int channels, int bits, const uint16_t *px,
    int srgb, int ntext, const struct png_text_kv *text, char **cause);
/* Read any PNG as 16-bit samples (8-bit values scaled by 257); caller frees.
 * Reports channels (1..4) and original bit depth. */
uint16_t *pngio_read(const char *path, int *w, int *h, int *channels, int *bits, char **cause);
/* Row streams, for images too large to hold whole (maps fit): the same
 * files and samples as pngio_write and pngio_read, a band of rows at a
 * time.  Every call that fails returns -1 (NULL) and *cause; then only
 * pngio_writer_abort (which removes the temporary file) or
 * pngio_reader_close may follow. */
struct pngio_writer;
struct pngio_writer *pngio_writer_open(const char *path, int w, int h, int channels, int bits,
    int srgb,
    int ntext, const struct png_text_kv *text, char **cause);
/* Rows y .. y + nrows - 1 in order, px as pngio_write's (w*channels per row). */
int pngio_writer_rows(struct pngio_writer *wr, const uint16_t *px, int nrows, char **cause);
/* After the last row: finish the file and rename it into place; frees wr. */
int pngio_writer_close(struct pngio_writer *wr, char **cause);
void pngio_writer_abort(struct pngio_writer *wr);	/* NULL is a no-op */

struct pngio_reader;
/* Open PATH and read its header (the same checks as pngio_read). */
struct pngio_reader *pngio_reader_open(const char *path, int *w, int *h, int *channels, int *bits,
    char **cause);
/* The next nrows rows as 16-bit samples, as pngio_read gives them. */
int pngio_reader_rows(struct pngio_reader *rd, uint16_t *px, int nrows, char **cause);
void pngio_reader_close(struct pngio_reader *rd);	/* NULL is a no-op */

/* The value of a tEXt keyword (caller frees), or NULL. */
char *pngio_read_text(const char *path, const char *key);
#endif
