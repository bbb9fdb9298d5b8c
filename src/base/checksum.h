/* checksum: SHA-256 of the data files of an output, kept in its manifest
 * as a member "checksums": {"NAME": "sha256:HEX", ...} (NAME relative to
 * the output directory), so that every reader (eval, verify, the
 * exporters, import_skin.py) finds a changed or damaged file before using
 * it.  SHA-256 through OpenSSL's libcrypto. */
#ifndef SKINBAKE_CHECKSUM_H
#define SKINBAKE_CHECKSUM_H

#define CHECKSUM_TEXT 72	/* "sha256:" + 64 hex digits + NUL, rounded up */

/* The checksum of the file PATH as "sha256:HEX" into out; -1 and *cause
 * (caller frees) when it cannot be read. */
int checksum_file(const char *path, char out[CHECKSUM_TEXT], char **cause);
/* The member text `"checksums": {"A": "sha256:..", ...}` for the files
 * NAMES (NULL-terminated, relative to DIR), for a manifest; NULL and
 * *cause when one cannot be read.  Caller frees. */
char *checksum_member(const char *dir, const char *const *names, char **cause);
/* checksum_member for every regular file of DIR but MANIFEST and names
 * starting with '.', and for the manifest.json of each subdirectory (a
 * family's members, whose own manifests list their files), in name order. */
char *checksum_member_dir(const char *dir, const char *manifest, char **cause);
/* MANIFEST's text with the checksums of DIR's files (checksum_member_dir)
 * added; NULL and *cause.  Caller frees. */
char *checksum_manifest_text(const char *dir, const char *manifest, const char *text, char **cause);
/* Write DIR/MANIFEST (all or nothing, base/util.h outfile) holding TEXT
 * with the checksums of DIR's files added: call it when every other file
 * is written.  -1 and *cause. */
int checksum_write_manifest(const char *dir, const char *manifest, const char *text, char **cause);
/* Check every file the manifest DIR/MANIFEST lists under "checksums"
 * (nothing to check when it has none: outputs from before checksums);
 * -1 and *cause for a changed, missing or unreadable file, or a name that
 * leaves DIR. */
int checksum_verify_dir(const char *dir, const char *manifest, char **cause);
/* The JSON object text MANIFEST (ending with '}' and blanks) with MEMBER
 * added as its last member; caller frees. */
char *checksum_add_member(const char *manifest, const char *member);
/* Does DIR/NAME have checksum WANT ("sha256:HEX")?  0, or -1 and *cause
 * naming the file and saying it changed since the manifest was written. */
int checksum_verify(const char *dir, const char *name, const char *want, char **cause);
#endif
