/* The memory of each member's step, fetched ahead (see member_prefetch.h). */
#include "member_prefetch.h"

#include <stdlib.h>

#include "component.h"
#include "error.h"

enum { LINE = 64 };

int member_prefetch_prepare(ssx_system *sys)
{
    member_prefetch_free(sys);
    struct member_lines *table = malloc(((size_t)sys->n_components + 1) * sizeof *table);
    if (table == NULL) {
        return fail(sys, -1, -1, sys->time, "out of memory preparing the schedule of '%s'",
                    sys->name);
    }
    for (int k = 0; k < sys->n_components; ++k) {
        const ssx_component *c = sys->components[sys->order[k]];
        const char *block = (const char *)c;
        const char *data = c->data != NULL ? (const char *)c->data : block;
        const ssx_fmu *fmu = c->ops->fmu != NULL ? c->ops->fmu(c) : NULL;
        const char *binding = fmu != NULL ? (const char *)fmu : block;
        /* the component's fields first read, its kind's data (next to it), its links and the
         * first two lines of its FMU binding (fmu_binding.c keeps a step's fields there) */
        table[k] = (struct member_lines){.line = {block, block + LINE, data, data + LINE,
                                                  data + 2 * LINE, c->links, binding,
                                                  binding + LINE}};
    }
    sys->member_lines = table;
    return 0;
}

void member_prefetch_free(ssx_system *sys)
{
    free(sys->member_lines);
    sys->member_lines = NULL;
}
