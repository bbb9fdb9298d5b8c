/* Shared helpers of the fuzz targets (tests/fuzz/fuzz_*.c).  Each target
 * defines LLVMFuzzerTestOneInput; it is linked either with libFuzzer
 * (./configure --enable-fuzzing, clang) or with replay.c, a plain-C main that
 * runs the committed corpus in every build. */
#ifndef SKINBAKE_FUZZ_H
#define SKINBAKE_FUZZ_H
#include <stddef.h>
#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
/* Optional one-time set-up; replay.c calls it too. */
int LLVMFuzzerInitialize(int *argc, char ***argv);

/* A path whose content is exactly data[0..size) (a memfd reached through
 * /proc/self/fd, so nothing touches the disk); valid until the next call. */
const char *fuzz_file(const uint8_t *data, size_t size);
/* data as a NUL-terminated string (caller frees). */
char *fuzz_text(const uint8_t *data, size_t size);
/* Abort with a message: a broken invariant is a finding like a crash. */
void fuzz_fail(const char *fmt, ...) __attribute__((format(printf, 1, 2), noreturn));
/* Why an input was refused, printed when SKINBAKE_FUZZ_VERBOSE is set
 * (to see what a corpus file exercises); frees cause. */
void fuzz_refused(char *cause);
/* tests/fuzz/data in the source tree (SKINBAKE_FUZZ_DATA overrides). */
const char *fuzz_datadir(void);
#endif
