/* The fuzz target of the modelDescription reader: any bytes are read, and what is accepted is
 * walked the way Python walks it (names joined, each name found again, every string offset
 * inside the pool). Built by libFuzzer (scripts/fuzz.sh) and by replay.c for `meson test`. */
#include "syssimx_engine.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void walk(const ssx_md *md)
{
    size_t joined_size = ssx_md_join(md, md->name, md->variable_count, NULL, 0);
    char *joined = malloc(joined_size > 0 ? joined_size : 1);
    if (joined == NULL) {
        return;
    }
    if (ssx_md_join(md, md->name, md->variable_count, joined, joined_size) != joined_size) {
        abort();
    }
    free(joined);
    for (size_t i = 0; i < md->variable_count; ++i) {
        int64_t first = ssx_md_find(md, md->strings + md->name[i]);
        if (first < 0 || first > (int64_t)i ||
            strcmp(md->strings + md->name[first], md->strings + md->name[i]) != 0) {
            abort(); /* every name is found, as its first variable */
        }
        ssx_md_join(md, &md->description[i], 1, NULL, 0);
        ssx_md_join(md, &md->start[i], 1, NULL, 0);
        ssx_md_join(md, &md->unit[i], 1, NULL, 0);
    }
    for (size_t i = 0; i < md->output_count; ++i) {
        if (md->output[i] >= md->variable_count) {
            abort();
        }
        for (int64_t k = 0; k < md->dependency_count[i]; ++k) {
            if (md->dependencies[md->first_dependency[i] + (size_t)k] >= md->variable_count) {
                abort();
            }
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* an exact-size copy: a read one past the end is a sanitizer report, not a lucky byte */
    char *text = malloc(size > 0 ? size : 1);
    if (text == NULL) {
        return 0;
    }
    memcpy(text, data, size);
    ssx_md *md = ssx_md_read(text, size);
    if (md != NULL && md->error.problem == SSX_MD_OK) {
        walk(md);
    } else if (md != NULL && md->error.problem == SSX_MD_NOT_XML &&
               (md->error.detail[0] == '\0' || md->error.line == 0)) {
        abort(); /* a refusal names what and where */
    }
    ssx_md_free(md);
    free(text);
    return 0;
}
