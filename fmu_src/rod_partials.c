/* PLACEHOLDER until the partials branch lands: d der(x)/d x only. */
#include "rod_partials.h"

#include <string.h>

void rod_partials(const RodParams *p, RodMode m, const double x[ROD_NX], RodPartials *d)
{
    memset(d, 0, sizeof *d);
    rod_jacobian(p, m, x, d->dx_x);
}
