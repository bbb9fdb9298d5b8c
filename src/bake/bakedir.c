/* bakedir: freeing a bake directory in memory (bakedir.h). */
#include "config.h"

#include "bake/bakedir.h"

#include <stdlib.h>

void bake_free(struct bake *b)
{
	if (b == NULL)
		return;
	free(b->dir);
	free(b->preset);
	free(b->wl_nm);
	free(b->theta_i);
	free(b->theta_o);
	free(b->phi);
	free(b->fr);
	free(b->fr_err);
	free(b->fr_rgb);
	free(b->albedo);
	free(b->rd_r_rgb);
	free(b->albedo_rgb);
	free(b->rgb_from_wl);
	free(b->stack);
	free(b->ms);
	free(b->macro);
	free(b->sss_radius_cm);
	free(b->points);
	free(b->theta_o_nodes);
	free(b->phi_nodes);
	free(b->interp);	/* one allocation (bakeinterp.c) */
	free(b);
}
