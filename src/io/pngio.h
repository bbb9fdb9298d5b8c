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
/* The value of a tEXt keyword (caller frees), or NULL. */
char *pngio_read_text(const char *path, const char *key);
#endif
