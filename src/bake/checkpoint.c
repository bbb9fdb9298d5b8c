/* checkpoint: a bake's solver states saved to OUT.checkpoint and restored
 * with --resume (see checkpoint.h). */
#include "config.h"
#include "bake/checkpoint.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/lock.h"
#include "base/util.h"

static const char MAGIC[] = "skinbake checkpoint 1\n";
/* Checkpoints of units (family members) are append-only: the same header
 * (magic, identity, count), then each record followed by a chained FNV-1a
 * hash (of the previous record's hash, or of the header's magic and
 * identity, and the record's bytes).  A save appends the new records,
 * syncs them, then writes the count in place and syncs again, so the file
 * always holds a complete earlier checkpoint: the records past the count
 * (an append cut short) are ignored and cut off by the next save.  Each
 * save writes only the new members (the whole file once grew to 98 MB per
 * save on the 8 x 6 family, 15 % of its CPU). */
static const char MAGIC_UNITS[] = "skinbake checkpoint 2\n";
enum { NAME_MAX_CK = 16, COUNT_AT = sizeof MAGIC + sizeof(uint64_t) };

struct record {
	unsigned char *state;	/* packed by the method; NULL: none yet */
	size_t len;
	uint32_t done;		/* 1: the run finished */
	char method[NAME_MAX_CK];
};

struct checkpoint {
	char *path, *tmp;
	uint64_t id;
	int write;		/* 1: this process writes the file */
	double every_s, last;	/* interval [s], time of the last write (util_now) */
	struct record *rec;	/* [n] the runs saved or loaded */
	int n, cap;
	int n_loaded;		/* runs read from the file */
	int seq;		/* solver runs begun in this process */
	const char *unit;	/* what a record is, for the note: "solver run" or "member" */
	int units;		/* 1: the append-only file of units (MAGIC_UNITS) */
	int n_saved;		/* units: records in the file (its count) */
	off_t end;		/* units: bytes of the file up to its last counted record */
	uint64_t chain;		/* units: the hash after the last counted record */
	char *note, *error;
	struct solver_ckpt hooks;
	struct lock *lock;	/* held while this process writes the file (base/lock.h) */
};

static uint64_t fnv(uint64_t h, const void *v, size_t n)
{
	const unsigned char *p = v;
	for (size_t i = 0; i < n; i++)
		h = (h ^ p[i]) * 0x100000001b3ULL;
	return h;
}
#define FNV0 0xcbf29ce484222325ULL

char *checkpoint_path(const char *out)
{
	size_t n = strlen(out);
	while (n > 1 && out[n - 1] == '/')
		n--;
	return xasprintf("%.*s.checkpoint", (int)n, out);
}

uint64_t checkpoint_seed(void)
{
	return fnv(FNV0, MAGIC, sizeof MAGIC);
}

/* The whole file in memory; NULL and *cause. */
static unsigned char *slurp(const char *path, size_t *len, char **cause)
{
	FILE *f = fopen(path, "rb");
	if (f == NULL) {
		*cause = xasprintf("%s: %s", path, strerror(errno));
		return NULL;
	}
	/* A regular file, read up to its size: a device or FIFO in its place
	 * (/dev/zero) would be read without end. */
	struct stat st;
	if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
		fclose(f);
		*cause = xasprintf("%s is not a regular file; remove it to bake from the start", path);
		return NULL;
	}
	size_t cap = (size_t)st.st_size + 1, n = 0, got;
	unsigned char *b = xmalloc(cap);
	while (n < cap && (got = fread(b + n, 1, cap - n, f)) > 0)
		n += got;
	int bad = ferror(f) || n == cap;	/* grew while read: not a checkpoint at rest */
	fclose(f);
	if (bad) {
		free(b);
		*cause = xasprintf("%s: read error", path);
		return NULL;
	}
	*len = n;
	return b;
}

static int wrong_id(struct checkpoint *c, uint64_t id, char **cause)
{
	*cause = xasprintf("%s was written by a different bake (identity %016llx; this command's is %016llx: "
	    "another preset, wavelengths, angles, grid, solver setting or seed); run that command with --resume, "
	    "or remove the file", c->path, (unsigned long long)id, (unsigned long long)c->id);
	return -1;
}

/* The append-only file of units b[len] (frees b) into c->rec. */
static int load_units(struct checkpoint *c, unsigned char *b, size_t len, char **cause)
{
	struct solver_buf in = { .p = b, .len = len };
	char magic[sizeof MAGIC_UNITS];
	uint64_t id = 0;
	uint32_t n = 0;
	solver_buf_get(&in, magic, sizeof magic);
	solver_buf_get(&in, &id, sizeof id);
	solver_buf_get(&in, &n, sizeof n);
	if (in.bad || memcmp(magic, MAGIC_UNITS, sizeof MAGIC_UNITS) != 0) {
		free(b);
		*cause = xasprintf("%s is not a complete skinbake checkpoint (damaged, or of "
		    "another version); remove it to bake from the start", c->path);
		return -1;
	}
	if (id != c->id) {
		free(b);
		return wrong_id(c, id, cause);
	}
	uint64_t h = fnv(FNV0, b, sizeof MAGIC_UNITS + sizeof id);
	if (n > len)
		in.bad = 1;
	c->rec = xcalloc(n && !in.bad ? n : 1, sizeof *c->rec);
	c->cap = n && !in.bad ? (int)n : 1;
	for (uint32_t i = 0; i < n && !in.bad; i++) {
		struct record *r = &c->rec[i];
		size_t at = in.pos;
		uint64_t sum = 0;
		solver_buf_get(&in, &r->done, sizeof r->done);
		solver_buf_get(&in, r->method, sizeof r->method);
		solver_buf_get(&in, &r->len, sizeof r->len);
		if (in.bad || r->len > in.len - in.pos || in.len - in.pos - r->len < sizeof sum) {
			in.bad = 1;
			break;
		}
		in.pos += r->len;
		h = fnv(h, b + at, in.pos - at);
		solver_buf_get(&in, &sum, sizeof sum);
		if (sum != h) {
			in.bad = 1;
			break;
		}
		r->state = xmalloc(r->len ? r->len : 1);
		memcpy(r->state, b + in.pos - sizeof sum - r->len, r->len);
		r->method[NAME_MAX_CK - 1] = '\0';
		c->n = (int)i + 1;
	}
	free(b);
	if (in.bad) {
		*cause = xasprintf("%s: its records are inconsistent; remove it to bake from the "
		    "start", c->path);
		return -1;
	}
	c->n_loaded = c->n_saved = c->n;
	c->end = (off_t)in.pos;
	c->chain = h;
	c->note = xasprintf("resuming from %s: %d member%s finished\n", c->path, c->n,
	    c->n == 1 ? "" : "s");
	return 0;
}

/* Parse the file into c->rec; -1 and *cause when it is damaged or foreign. */
static int load(struct checkpoint *c, char **cause)
{
	size_t len;
	unsigned char *b = slurp(c->path, &len, cause);
	if (b == NULL)
		return -1;
	struct solver_buf in = { .p = b, .len = len };
	char magic[sizeof MAGIC];
	uint64_t id, sum, want = len >= 8 ? fnv(FNV0, b, len - 8) : 0;
	uint32_t n = 0;
	solver_buf_get(&in, magic, sizeof magic);
	if (c->units)
		return load_units(c, b, len, cause);
	if (in.bad || memcmp(magic, MAGIC, sizeof MAGIC) != 0 || (memcpy(&sum, b + len - 8, 8), sum != want)) {
		*cause = xasprintf("%s is not a complete skinbake checkpoint (damaged, or of another version); remove it "
		    "to bake from the start", c->path);
		free(b);
		return -1;
	}
	in.len -= 8;
	solver_buf_get(&in, &id, sizeof id);
	if (id != c->id) {
		free(b);
		return wrong_id(c, id, cause);
	}
	solver_buf_get(&in, &n, sizeof n);
	if (n > len) {
		in.bad = 1;
		n = 0;
	}
	c->rec = xcalloc(n ? n : 1, sizeof *c->rec);
	c->cap = n ? (int)n : 1;
	for (uint32_t i = 0; i < n && !in.bad; i++) {
		struct record *r = &c->rec[i];
		solver_buf_get(&in, &r->done, sizeof r->done);
		solver_buf_get(&in, r->method, sizeof r->method);
		solver_buf_get(&in, &r->len, sizeof r->len);
		if (in.bad || r->len > in.len - in.pos) {
			in.bad = 1;
			break;
		}
		r->state = xmalloc(r->len ? r->len : 1);
		solver_buf_get(&in, r->state, r->len);
		r->method[NAME_MAX_CK - 1] = '\0';
		c->n = (int)i + 1;
	}
	free(b);
	if (in.bad || in.pos != in.len) {
		*cause = xasprintf("%s: its records are inconsistent; remove it to bake from the start", c->path);
		return -1;
	}
	c->n_loaded = c->n;
	int done = 0;
	for (int i = 0; i < c->n; i++)
		done += c->rec[i].done != 0;
	if (strcmp(c->unit, "member") == 0)	/* members are saved only when finished */
		c->note = xasprintf("resuming from %s: %d member%s finished\n", c->path, done, done == 1 ? "" : "s");
	else
		c->note = xasprintf("resuming from %s: %d %s%s finished, %d in progress\n", c->path, done, c->unit,
		    done == 1 ? "" : "s", c->n - done);
	return 0;
}

/* All n bytes of v to fd at offset at (pwrite, retried on EINTR and short writes). */
static int write_at(int fd, const void *v, size_t n, off_t at)
{
	const unsigned char *p = v;
	while (n > 0) {
		ssize_t k = pwrite(fd, p, n, at);
		if (k < 0 && errno == EINTR)
			continue;
		if (k <= 0)
			return -1;
		p += k;
		n -= (size_t)k;
		at += k;
	}
	return 0;
}

/* fsync of the directory holding c->path (after a rename or a creation). */
static void sync_dir(const struct checkpoint *c)
{
	char *slash = strrchr(c->path, '/');
	char *dir = slash ? xasprintf("%.*s", slash == c->path ? 1 : (int)(slash - c->path), c->path) : xstrdup(".");
	int dfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
	if (dfd >= 0) {
		fsync(dfd);
		close(dfd);
	}
	free(dir);
}

/* The records to path.tmp, fsync, rename onto path, fsync of the directory. */
static int save_file(struct checkpoint *c, char **cause)
{
	struct solver_buf b = { 0 };
	uint32_t n = (uint32_t)c->n;
	solver_buf_put(&b, MAGIC, sizeof MAGIC);
	solver_buf_put(&b, &c->id, sizeof c->id);
	solver_buf_put(&b, &n, sizeof n);
	for (int i = 0; i < c->n; i++) {
		const struct record *r = &c->rec[i];
		solver_buf_put(&b, &r->done, sizeof r->done);
		solver_buf_put(&b, r->method, sizeof r->method);
		solver_buf_put(&b, &r->len, sizeof r->len);
		solver_buf_put(&b, r->state, r->len);
	}
	uint64_t sum = fnv(FNV0, b.p, b.len);
	solver_buf_put(&b, &sum, sizeof sum);
	int fd = open(c->tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
	int rc = fd < 0 || write_at(fd, b.p, b.len, 0) != 0 || fsync(fd) != 0 ? -1 : 0;
	int err = errno;
	if (fd >= 0 && close(fd) != 0 && rc == 0) {
		rc = -1;
		err = errno;
	}
	if (rc == 0 && rename(c->tmp, c->path) != 0) {
		rc = -1;
		err = errno;
	}
	free(b.p);
	if (rc != 0) {
		unlink(c->tmp);
		*cause = xasprintf("%s: %s", c->path, strerror(err));
		return -1;
	}
	sync_dir(c);
	return 0;
}

/* Units: append the records not yet in the file (see MAGIC_UNITS), then
 * the count; the appended states are freed (they are never read back). */
static int save_units(struct checkpoint *c, char **cause)
{
	int fresh = c->end == 0;
	int fd = open(c->path, O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
	struct solver_buf b = { 0 };
	uint32_t n = (uint32_t)c->n;
	uint64_t h = c->chain;
	if (fresh) {
		uint32_t zero = 0;
		solver_buf_put(&b, MAGIC_UNITS, sizeof MAGIC_UNITS);
		solver_buf_put(&b, &c->id, sizeof c->id);
		h = fnv(FNV0, b.p, b.len);
		solver_buf_put(&b, &zero, sizeof zero);
	}
	for (int i = c->n_saved; i < c->n; i++) {
		const struct record *r = &c->rec[i];
		size_t at = b.len;
		solver_buf_put(&b, &r->done, sizeof r->done);
		solver_buf_put(&b, r->method, sizeof r->method);
		solver_buf_put(&b, &r->len, sizeof r->len);
		solver_buf_put(&b, r->state, r->len);
		h = fnv(h, b.p + at, b.len - at);
		solver_buf_put(&b, &h, sizeof h);
	}
	int rc = fd < 0 || ftruncate(fd, c->end) != 0 || write_at(fd, b.p, b.len, c->end) != 0 ||
	    fdatasync(fd) != 0 || write_at(fd, &n, sizeof n, COUNT_AT) != 0 || fdatasync(fd) != 0 ?
	    -1 : 0;
	int err = errno;
	if (fd >= 0 && close(fd) != 0 && rc == 0) {
		rc = -1;
		err = errno;
	}
	if (rc != 0) {
		free(b.p);
		*cause = xasprintf("%s: %s", c->path, strerror(err));
		return -1;
	}
	if (fresh)
		sync_dir(c);
	c->end += (off_t)b.len;
	c->chain = h;
	for (int i = c->n_saved > c->n_loaded ? c->n_saved : c->n_loaded; i < c->n; i++) {
		free(c->rec[i].state);
		c->rec[i].state = NULL;
	}
	c->n_saved = c->n;
	free(b.p);
	return 0;
}

static int hook_restore(void *user, const struct solver_ops *ops, void *state, char **cause)
{
	struct checkpoint *c = user;
	int k = c->seq++;
	if (k >= c->n_loaded)
		return 0;
	const struct record *r = &c->rec[k];
	if (strcmp(r->method, ops->name) != 0 || ops->unpack(state, r->state, r->len) != 0) {
		*cause = xasprintf("%s: solver run %d does not fit this bake (saved by '%s', now '%s'); remove the file "
		    "to bake from the start", c->path, k + 1, r->method, ops->name);
		return -1;
	}
	return r->done ? 1 : 0;
}

static void hook_save(void *user, const struct solver_ops *ops, const void *state, int done)
{
	struct checkpoint *c = user;
	int k = c->seq - 1;
	if (!c->write || ops->pack == NULL || k < 0)
		return;
	if (k >= c->cap) {
		c->rec = xreallocarray(c->rec, (size_t)(c->cap = 2 * k + 4), sizeof *c->rec);
		memset(c->rec + c->n, 0, sizeof *c->rec * (size_t)(c->cap - c->n));
	}
	if (k >= c->n)
		c->n = k + 1;
	struct record *r = &c->rec[k];
	free(r->state);
	r->state = ops->pack(state, &r->len);
	r->done = (uint32_t)done;
	snprintf(r->method, sizeof r->method, "%s", ops->name);
	double now = util_now();
	if (c->error == NULL && now - c->last >= c->every_s) {
		if (save_file(c, &c->error) == 0)
			c->last = now;
	}
}

/* checkpoint_open with the identity given (records of unit). */
static struct checkpoint *open_id(const char *out, uint64_t id, const char *unit, int resume, int write, double every_s,
    char **cause)
{
	struct checkpoint *c = xcalloc(1, sizeof *c);
	c->units = strcmp(unit, "member") == 0;
	c->path = checkpoint_path(out);
	c->tmp = xasprintf("%s.tmp", c->path);
	c->id = id;
	c->unit = unit;
	c->write = write;
	c->every_s = every_s;
	c->hooks = (struct solver_ckpt){ hook_restore, hook_save, c };
	/* One writer per checkpoint: a bake still running is never resumed. */
	if (write && (c->lock = lock_take(c->path, cause)) == NULL) {
		checkpoint_close(c);
		return NULL;
	}
	struct stat st;
	int there = stat(c->path, &st) == 0;
	if (there && !resume)
		*cause = xasprintf("%s: a checkpoint of an interrupted bake is there; pass --resume to continue it (the same "
		    "command), or remove the file to bake from the start", c->path);
	if ((there && !resume) || (there && load(c, cause) != 0)) {
		checkpoint_close(c);
		return NULL;
	}
	if (write)
		unlink(c->tmp);	/* a write cut short by the kill */
	if (c->note == NULL)
		c->note = xstrdup("");
	c->last = util_now();
	return c;
}

struct checkpoint *checkpoint_open(const char *out, uint64_t id, int resume, int write, double every_s, char **cause)
{
	return open_id(out, id, "solver run", resume, write, every_s, cause);
}

uint64_t checkpoint_hash(uint64_t h, const void *v, size_t n)
{
	return fnv(h ? h : FNV0, v, n);
}

struct checkpoint *checkpoint_open_units(const char *out, uint64_t id, int resume, int write, double every_s,
    char **cause)
{
	return open_id(out, id, "member", resume, write, every_s, cause);
}

int checkpoint_units(const struct checkpoint *c)
{
	int k = 0;
	while (k < c->n_loaded && c->rec[k].done && strcmp(c->rec[k].method, "member") == 0)
		k++;
	return k;
}

const void *checkpoint_unit(const struct checkpoint *c, int k, size_t *len)
{
	*len = c->rec[k].len;
	return c->rec[k].state;
}

void checkpoint_unit_add(struct checkpoint *c, const void *state, size_t len)
{
	if (!c->write)
		return;
	if (c->n >= c->cap) {
		c->rec = xreallocarray(c->rec, (size_t)(c->cap = 2 * c->n + 4), sizeof *c->rec);
		memset(c->rec + c->n, 0, sizeof *c->rec * (size_t)(c->cap - c->n));
	}
	struct record *r = &c->rec[c->n++];
	r->state = xmalloc(len ? len : 1);
	memcpy(r->state, state, len);
	r->len = len;
	r->done = 1;
	snprintf(r->method, sizeof r->method, "member");
	double now = util_now();
	if (c->error == NULL && now - c->last >= c->every_s && save_units(c, &c->error) == 0)
		c->last = now;
}

const struct solver_ckpt *checkpoint_hooks(struct checkpoint *c)
{
	return &c->hooks;
}

const char *checkpoint_note(const struct checkpoint *c)
{
	return c->note;
}

const char *checkpoint_write_error(const struct checkpoint *c)
{
	return c->error;
}

void checkpoint_close(struct checkpoint *c)
{
	if (c == NULL)
		return;
	for (int i = 0; i < c->n; i++)
		free(c->rec[i].state);
	free(c->rec);
	free(c->path);
	free(c->tmp);
	free(c->note);
	free(c->error);
	lock_release(c->lock);
	free(c);
}

int checkpoint_remove(const char *out, char **cause)
{
	char *path = checkpoint_path(out);
	int rc = unlink(path) == 0 || errno == ENOENT ? 0 : -1;
	if (rc != 0)
		*cause = xasprintf("%s: %s", path, strerror(errno));
	free(path);
	return rc;
}
