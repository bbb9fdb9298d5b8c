/* checksum: SHA-256 of files for the manifests (checksum.h). */
#include "config.h"
#include "base/checksum.h"

#include <dirent.h>
#include <errno.h>
#include <json-c/json.h>
#include <openssl/evp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/util.h"

int checksum_file(const char *path, char out[CHECKSUM_TEXT], char **cause)
{
	FILE *f = fopen(path, "rb");
	if (f == NULL) {
		*cause = xasprintf("%s: %s", path, strerror(errno));
		return -1;
	}
	EVP_MD_CTX *c = EVP_MD_CTX_new();
	int ok = c != NULL && EVP_DigestInit_ex(c, EVP_sha256(), NULL) == 1;
	unsigned char buf[1 << 16], md[EVP_MAX_MD_SIZE];
	unsigned int len = 0;
	size_t n;
	while (ok && (n = fread(buf, 1, sizeof buf, f)) > 0)
		ok = EVP_DigestUpdate(c, buf, n) == 1;
	int read_error = ferror(f);
	fclose(f);
	ok = ok && !read_error && EVP_DigestFinal_ex(c, md, &len) == 1 && len == 32;
	EVP_MD_CTX_free(c);
	if (!ok) {
		const char *why = read_error ? "read error" : "cannot compute its SHA-256";
		*cause = xasprintf("%s: %s", path, why);
		return -1;
	}
	strcpy(out, "sha256:");
	for (unsigned int i = 0; i < len; i++)
		snprintf(out + 7 + 2 * i, 3, "%02x", md[i]);
	return 0;
}

char *checksum_member(const char *dir, const char *const *names, char **cause)
{
	char *m = xstrdup("\"checksums\": {");
	for (int i = 0; names[i]; i++) {
		char *p = xasprintf("%s/%s", dir, names[i]), sum[CHECKSUM_TEXT];
		int rc = checksum_file(p, sum, cause);
		free(p);
		if (rc != 0) {
			free(m);
			return NULL;
		}
		/* The names are the writers' own (plain ASCII): no escaping needed. */
		char *n = xasprintf("%s%s\"%s\": \"%s\"", m, i ? ", " : "", names[i], sum);
		free(m);
		m = n;
	}
	char *n = xasprintf("%s}", m);
	free(m);
	return n;
}

static int is_blank(char c)
{
	return c == ' ' || c == '\n' || c == '\t';
}

char *checksum_add_member(const char *manifest, const char *member)
{
	size_t end = strlen(manifest);
	while (end > 0 && manifest[end - 1] != '}')
		end--;
	if (end == 0)
		return xstrdup(manifest);
	size_t body = end - 1;	/* the closing brace */
	size_t last = body;
	while (last > 0 && is_blank(manifest[last - 1]))
		last--;
	int empty = last > 0 && manifest[last - 1] == '{';
	return xasprintf("%.*s%s\n  %s\n}\n", (int)last, manifest, empty ? "" : ",", member);
}

int checksum_verify(const char *dir, const char *name, const char *want, char **cause)
{
	char *p = xasprintf("%s/%s", dir, name), have[CHECKSUM_TEXT];
	int rc = checksum_file(p, have, cause);
	if (rc == 0 && strcmp(have, want) != 0) {
		*cause = xasprintf("%s has changed since its manifest was written (%s there, %s "
		    "expected): the file was edited or damaged; write the output again", p, have,
		    want);
		rc = -1;
	}
	free(p);
	return rc;
}

static int cmp_str(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

struct name_list {
	char **names;
	size_t n, cap;
};

static void name_add(struct name_list *l, char *name)
{
	if (l->n + 2 > l->cap)
		l->names = xreallocarray(l->names, l->cap = 2 * l->cap + 16, sizeof *l->names);
	l->names[l->n++] = name;
}

/* Add the regular files of DIR/SUB (SUB NULL: DIR itself) but SKIP, as
 * "SUB/NAME" or "NAME".  At the top, a subdirectory with a manifest.json is
 * a member output (a family's mNNNN): its data files are added, not its
 * manifest: that holds run times, and a checksum over it would make the
 * outer manifest differ between two identical runs (resume and kill tests).
 * 0, or -1 when DIR/SUB cannot be read. */
static int add_files(struct name_list *l, const char *dir, const char *sub, const char *skip)
{
	char *p = sub ? xasprintf("%s/%s", dir, sub) : xstrdup(dir);
	DIR *d = opendir(p);
	if (d == NULL) {
		int err = errno;
		free(p);
		errno = err;
		return -1;
	}
	struct dirent *e;
	while ((e = readdir(d)) != NULL) {
		if (e->d_name[0] == '.' || strcmp(e->d_name, skip) == 0)
			continue;
		char *f = xasprintf("%s/%s", p, e->d_name);
		char *m = xasprintf("%s/manifest.json", f);
		struct stat st;
		/* else gone since readdir: not part of the output */
		int here = lstat(f, &st) == 0;
		if (here && S_ISREG(st.st_mode))
			name_add(l, sub ? xasprintf("%s/%s", sub, e->d_name) : xstrdup(e->d_name));
		else if (here && sub == NULL && S_ISDIR(st.st_mode) && access(m, F_OK) == 0)
			(void)add_files(l, dir, e->d_name, "manifest.json");
		free(m);
		free(f);
	}
	closedir(d);
	free(p);
	return 0;
}

char *checksum_member_dir(const char *dir, const char *manifest, char **cause)
{
	struct name_list l = { NULL, 0, 0 };
	if (add_files(&l, dir, NULL, manifest) != 0) {
		*cause = xasprintf("%s: %s", dir, strerror(errno));
		return NULL;
	}
	if (l.n > 0)
		qsort(l.names, l.n, sizeof *l.names, cmp_str);
	l.names = xreallocarray(l.names, l.n + 1, sizeof *l.names);
	l.names[l.n] = NULL;
	char *sums = checksum_member(dir, (const char *const *)l.names, cause);
	for (size_t i = 0; i < l.n; i++)
		free(l.names[i]);
	free(l.names);
	return sums;
}

char *checksum_manifest_text(const char *dir, const char *manifest, const char *text, char **cause)
{
	char *m = checksum_member_dir(dir, manifest, cause);
	if (m == NULL)
		return NULL;
	char *t = checksum_add_member(text, m);
	free(m);
	return t;
}

/* Length of the valid UTF-8 sequence at s (1-4), or 0. */
static int utf8_len(const unsigned char *s)
{
	int n = 0;
	if (s[0] < 0x80)
		n = 1;
	else if (s[0] >= 0xC2 && s[0] <= 0xDF)
		n = 2;
	else if (s[0] >= 0xE0 && s[0] <= 0xEF)
		n = 3;
	else if (s[0] >= 0xF0 && s[0] <= 0xF4)
		n = 4;
	for (int i = 1; i < n; i++)
		if ((s[i] & 0xC0) != 0x80)
			return 0;
	if ((n == 3 && s[0] == 0xE0 && s[1] < 0xA0) || (n == 3 && s[0] == 0xED && s[1] >= 0xA0) ||
	    (n == 4 && s[0] == 0xF0 && s[1] < 0x90) || (n == 4 && s[0] == 0xF4 && s[1] >= 0x90))
		return 0;	/* overlong, surrogate, beyond U+10FFFF */
	return n;
}

/* TEXT (JSON) with every byte that is not UTF-8 written as the characters
 * \xHH (an escaped backslash in JSON): a path of any bytes, e.g. a
 * non-UTF-8 --out in "command", stays readable and the file stays JSON
 * that strict readers (Python's json, import_skin.py) take.  JSON syntax
 * is ASCII, so such bytes are only inside strings.  Caller frees. */
static char *utf8_safe(const char *text)
{
	size_t n = strlen(text), k = 0;
	char *out = xmalloc(5 * n + 1);
	for (const unsigned char *s = (const unsigned char *)text; *s;) {
		int len = utf8_len(s);
		if (len == 0) {
			k += (size_t)sprintf(out + k, "\\\\x%02X", *s);
			s++;
			continue;
		}
		memcpy(out + k, s, (size_t)len);
		k += (size_t)len;
		s += len;
	}
	out[k] = '\0';
	return out;
}

int checksum_write_manifest(const char *dir, const char *manifest, const char *text, char **cause)
{
	char *safe = utf8_safe(text);
	char *t = checksum_manifest_text(dir, manifest, safe, cause);
	free(safe);
	if (t == NULL)
		return -1;
	char *path = xasprintf("%s/%s", dir, manifest);
	int rc = outfile_write_text(path, t, cause);
	free(path);
	free(t);
	return rc;
}

int checksum_verify_dir(const char *dir, const char *manifest, char **cause)
{
	char *mp = xasprintf("%s/%s", dir, manifest);
	json_object *j = json_object_from_file(mp), *sums;
	int rc = 0;
	if (j == NULL || !json_object_object_get_ex(j, "checksums", &sums)) {
		free(mp);
		if (j)
			json_object_put(j);
		/* no manifest is the reader's own error; no checksums: an older output */
		return 0;
	}
	if (!json_object_is_type(sums, json_type_object)) {
		*cause = xasprintf("%s: checksums is not an object of \"FILE\": \"sha256:HEX\"",
		    mp);
		rc = -1;
	}
	json_object_object_foreach(sums, name, val) {
		if (rc != 0)
			break;
		const char *want = NULL;
		if (json_object_is_type(val, json_type_string))
			want = json_object_get_string(val);
		int bad = want == NULL || strncmp(want, "sha256:", 7) != 0 || strlen(want) != 71;
		if (bad || name[0] == '/' || strstr(name, "..") != NULL) {
			*cause = xasprintf("%s: checksums.%s: not a file of the directory with "
			    "\"sha256:\" and 64 hex digits", mp, name);
			rc = -1;
		} else
			rc = checksum_verify(dir, name, want, cause);
	}
	json_object_put(j);
	free(mp);
	return rc;
}
