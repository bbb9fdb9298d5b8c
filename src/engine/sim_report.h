/* sim_report: the results of one layer stack at one incidence angle (what
 * `skinbake simulate` prints) as text: one JSON object, or a readable
 * table.  Monte Carlo (sim_run) and adding-doubling (ad_sim_run) give
 * the same keys (Rsp, Rd, Tt, A, brdf_az, brdf with their _err fields); the
 * errors are standard errors for the one and the solver's error estimates
 * for the other, which also says "solver": "ad" and its resolution, and has
 * no photon counts or Rd(r).  Printing stays with the caller. */
#ifndef SKINBAKE_SIM_REPORT_H
#define SKINBAKE_SIM_REPORT_H
#include <stdio.h>
#include "engine/sim.h"
#include "engine/solver.h"

/* The JSON object (one line, caller frees).  ad = NULL: Monte Carlo's run
 * c; otherwise adding-doubling's, c giving the angle only. */
char *sim_report_json(const struct sim_config *c, const struct sim_result *r, const struct sim_solve_info *ad);
/* The readable table on fp; ad as above. */
void sim_report_table(FILE *fp, const struct sim_config *c, const struct sim_result *r, const struct sim_solve_info *ad);
#endif
