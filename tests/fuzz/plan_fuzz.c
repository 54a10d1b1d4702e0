/* The fuzz target of the plan reader: any bytes are read; a refusal names its line, and what
 * is accepted is written, read back and written again, which must give the same text. Built by
 * libFuzzer (scripts/fuzz.sh) and by replay.c for `meson test`. */
#include "syssimx_engine.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* an exact-size copy: a read one past the end is a sanitizer report, not a lucky byte */
    char *text = malloc(size > 0 ? size : 1);
    if (text == NULL) {
        return 0;
    }
    memcpy(text, data, size);
    char error[512];
    ssx_plan *plan = ssx_plan_read(text, size, error, sizeof error);
    free(text);
    if (plan == NULL) {
        if (strncmp(error, "line ", 5) != 0) {
            abort(); /* a refusal names where */
        }
        return 0;
    }
    size_t written_size = 0;
    char *written = ssx_plan_write(plan, &written_size);
    ssx_plan_free(plan);
    if (written == NULL) {
        return 0; /* out of memory */
    }
    ssx_plan *again = ssx_plan_read(written, written_size, error, sizeof error);
    if (again == NULL) {
        abort(); /* what the writer writes is read */
    }
    size_t rewritten_size = 0;
    char *rewritten = ssx_plan_write(again, &rewritten_size);
    if (rewritten != NULL && (rewritten_size != written_size ||
                              memcmp(rewritten, written, written_size) != 0)) {
        abort(); /* and written back the same */
    }
    ssx_plan_text_free(rewritten);
    ssx_plan_text_free(written);
    ssx_plan_free(again);
    return 0;
}
