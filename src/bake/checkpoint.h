/* checkpoint: a bake's progress in a file beside its output directory
 * (OUT.checkpoint), so that a bake killed on the way (power, OOM, a job
 * limit) continues with `--resume` and writes the same tables, byte for
 * byte, as one never stopped.
 *
 * A bake is a fixed sequence of solver runs (engine/solver.h: adding-
 * doubling, its Monte Carlo fallback, the Rd(r) pilot and reruns; or one
 * Monte Carlo run), each a sequence of steps (Monte Carlo: at most 32
 * batches per job; adding-doubling: a few wavelengths).  After each step
 * the driver hands the method's packed state to this module, which keeps
 * the latest state of every run in memory and writes all of them at most
 * every `every_s` seconds: OUT.checkpoint.tmp, fsync, rename, fsync of the
 * directory, so the file is always a complete earlier checkpoint.  On
 * resume, runs saved as finished are not run again and the run in progress
 * goes on from its last step.  The numbers depend only on the problem, the
 * settings and the seed (counter-based random numbers: the state is sums
 * and counters), so the continued bake equals the uninterrupted one.
 *
 * The file: "skinbake checkpoint 1\n", the identity of the bake (a 64-bit
 * FNV-1a hash of everything that changes the numbers: wavelengths, layer
 * stacks, angles, grid, methods and their settings, seed; not the thread
 * count or the output), the records (run index, done flag, method name, the
 * packed state), and an FNV-1a hash of all of it, so that a torn or foreign
 * file is refused.  The file holds the machine's number format. */
#ifndef SKINBAKE_CHECKPOINT_H
#define SKINBAKE_CHECKPOINT_H
#include <stdint.h>
#include "engine/solver.h"

#define CHECKPOINT_SECONDS 5.0	/* default interval between writes [s] */

struct checkpoint;

/* "OUT.checkpoint" for the output directory OUT (trailing '/' dropped); caller frees. */
char *checkpoint_path(const char *out);
/* The start of every identity: the hash of the file's magic line; a bake's
 * identity (bake_spec_identity, bake.h) goes on from it with
 * checkpoint_hash. */
uint64_t checkpoint_seed(void);

/* Open the checkpoint of the bake of identity ID (bake_spec_identity)
 * writing to out.  A checkpoint file
 * already there is an error without resume ("pass --resume or remove it"),
 * and with resume is read (an error when it is damaged or of another
 * bake); with resume and no file the bake starts from nothing.  write: 0
 * to only read (MPI ranks), 1 to write every every_s seconds (0: after
 * every step).  NULL and *cause on error. */
struct checkpoint *checkpoint_open(const char *out, uint64_t id, int resume, int write, double every_s, char **cause);
/* Checkpoints of units, for family bakes (family/family.h): the same file
 * format, one record per finished unit (a member's packed result, in
 * member order), under an identity the caller makes with checkpoint_hash
 * (seeded with 0 or with checkpoint_identity).  checkpoint_open_units acts
 * as checkpoint_open (same errors); checkpoint_units is how many units
 * were restored, checkpoint_unit the k-th of them (owned by c);
 * checkpoint_unit_add appends one (when c writes) and, when every_s
 * seconds have passed since the last write, appends the units not yet in
 * the file to it (an append-only file, "skinbake checkpoint 2": the units
 * already written are not written again; checkpoint.c). */
uint64_t checkpoint_hash(uint64_t h, const void *v, size_t n);
struct checkpoint *checkpoint_open_units(const char *out, uint64_t id, int resume, int write, double every_s,
    char **cause);
int checkpoint_units(const struct checkpoint *c);
const void *checkpoint_unit(const struct checkpoint *c, int k, size_t *len);
void checkpoint_unit_add(struct checkpoint *c, const void *state, size_t len);
/* The hooks for solver_run.ckpt. */
const struct solver_ckpt *checkpoint_hooks(struct checkpoint *c);
/* A line for the user about what was restored ("" when nothing was), and
 * the first write error (NULL if none); both owned by c. */
const char *checkpoint_note(const struct checkpoint *c);
const char *checkpoint_write_error(const struct checkpoint *c);
/* Free c (the file stays). */
void checkpoint_close(struct checkpoint *c);
/* Remove OUT.checkpoint after the bake's output is complete; 0, or -1 and
 * *cause. */
int checkpoint_remove(const char *out, char **cause);
#endif
