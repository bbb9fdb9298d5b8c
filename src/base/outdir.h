/* outdir: an output directory replaced as a whole.  The writer puts the
 * complete new set of files into a staging directory beside the target
 * (PARENT/.NAME.staging.HOST.PID); outdir_commit swaps it in with a single
 * rename, so that a reader sees the whole old set or the whole new one at
 * every instant, also when the process is killed at any point:
 *
 *   target absent   rename(staging, target)
 *   target present  renameat2(staging, target, RENAME_EXCHANGE) (Linux 3.15,
 *                   ext4, xfs, btrfs, tmpfs), then the old set, now under
 *                   the staging name, is removed
 *   no exchange     rename(target, .NAME.retired.HOST.PID), rename(staging,
 *                   target): between the two the target is absent, never
 *                   mixed, and the next run puts the retired set back
 *
 * Files are fsync'ed before the swap and the parent after it, so a power
 * cut also leaves one complete set.  Staging and retired directories of a
 * dead run (same host, process gone) are removed by the next outdir_begin
 * for that target.  A directory is replaced only when it holds a complete
 * output of the writer's kind and nothing else (outdir_check), so that no
 * file of a user's is ever removed with the old set. */
#ifndef SKINBAKE_OUTDIR_H
#define SKINBAKE_OUTDIR_H

struct lock;

/* What kind of output a directory holds, so that a writer replaces only an
 * output of its own kind.  Each writer's module defines its kind (e.g.
 * bake_outdir_kind in bake/bakefile.h). */
struct outdir_kind {
	const char *what;	/* "bake directory", for messages */
	const char *marker;	/* the manifest that marks a complete output: "manifest.json" */
	const char *key;	/* the manifest's member naming the kind ("format"); NULL: any marker file */
	const char *value;	/* its value: "skinbake-bake" */
	/* fnmatch patterns of the entries an output of this kind may hold
	 * besides those its manifest lists under "files" (for outputs written
	 * before manifests listed them); NULL: any entry */
	const char *const *names;
};

struct outdir {
	char *target;	/* the directory replaced (symbolic link resolved, no trailing '/') */
	char *parent;	/* the directory that holds target and staging */
	char *name;	/* target's last component */
	char *staging;	/* where the writer puts the new set; NULL after commit or abort */
	char *retired;	/* the old set's name when the swap cannot exchange */
	struct lock *lock;	/* held from begin to commit or abort (base/lock.h) */
};

/* May TARGET be replaced by an output of KIND?  Yes (0) when it does not
 * exist or is an empty directory, or holds a complete output of KIND: its
 * marker is a JSON object whose KEY is VALUE and every entry is listed in
 * the marker's "files" (array of names, or object keyed by name) or matches
 * one of KIND's names.  -1 and *cause (caller frees) otherwise, and for '/',
 * '.', '..', a non-directory, a dangling symbolic link, and a TARGET equal
 * to, inside or holding one of INPUTS (NULL-terminated paths the command
 * reads; may be NULL), whose replacement would destroy an input or put
 * files into it. */
int outdir_check(const char *target, const struct outdir_kind *kind, const char *const *inputs, char **cause);

/* Prepare to replace TARGET: outdir_check (without inputs); take TARGET's
 * lock (a second writer is refused, naming the first); create missing
 * parents; remove stale staging of dead runs; create a fresh staging
 * directory.  Call it before long work, so that a bad target fails early. */
int outdir_begin(struct outdir *o, const char *target, const struct outdir_kind *kind, char **cause);
/* The staging directory to write into (valid between begin and commit). */
const char *outdir_path(const struct outdir *o);
/* Swap the staging directory in as described above, release the lock and
 * free o's names.  -1 and *cause when the swap fails; the target is then
 * the old set, or the new one if only the removal of the old set failed
 * (that is not an error). */
int outdir_commit(struct outdir *o, char **cause);
/* Remove the staging directory and what is in it, release the lock, free
 * o's names.  For the error paths of writers; a no-op after commit. */
void outdir_abort(struct outdir *o);
/* outdir_abort after a failure whose *cause (may be NULL) names files in
 * the staging directory: they are named by the target instead, which is
 * what the user gave. */
void outdir_fail(struct outdir *o, char **cause);
/* Remove the staging and retired directories of dead runs beside TARGET
 * (the retired set is renamed back when the target is missing: it was
 * complete).  Returns how many were found; outdir_begin calls it. */
int outdir_clean_stale(const char *target);
#endif
