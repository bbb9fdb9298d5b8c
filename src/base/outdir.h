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
 * for that target.  Every file of the set belongs to it: files a user put
 * into an output directory are removed with the old set. */
#ifndef SKINBAKE_OUTDIR_H
#define SKINBAKE_OUTDIR_H

struct outdir {
	char *target;	/* the directory replaced (symbolic link resolved, no trailing '/') */
	char *parent;	/* the directory that holds target and staging */
	char *name;	/* target's last component */
	char *staging;	/* where the writer puts the new set; NULL after commit or abort */
	char *retired;	/* the old set's name when the swap cannot exchange */
};

/* Prepare to replace TARGET: refuse it (-1 and *cause, caller frees) when it
 * is empty, '.', '..' or '/', names something other than a directory, or is
 * a non-empty directory without the file MARKER (e.g. "manifest.json": so
 * that `--out $HOME` does not replace a home directory); create missing
 * parents; remove stale staging of dead runs; create a fresh staging
 * directory.  Call it before long work, so that a bad target fails early. */
int outdir_begin(struct outdir *o, const char *target, const char *marker, char **cause);
/* The staging directory to write into (valid between begin and commit). */
const char *outdir_path(const struct outdir *o);
/* Swap the staging directory in as described above and free o's names.
 * -1 and *cause when the swap fails; the target is then the old set, or the
 * new one if only the removal of the old set failed (that is not an error). */
int outdir_commit(struct outdir *o, char **cause);
/* Remove the staging directory and what is in it; free o's names.  For the
 * error paths of writers; a no-op after commit. */
void outdir_abort(struct outdir *o);
/* Remove the staging and retired directories of dead runs beside TARGET
 * (the retired set is renamed back when the target is missing: it was
 * complete).  Returns how many were found; outdir_begin calls it. */
int outdir_clean_stale(const char *target);
#endif
