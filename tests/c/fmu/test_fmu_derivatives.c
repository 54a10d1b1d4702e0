/* fmi2GetDirectionalDerivative against central differences of the outputs, at a point reached by
 * one step with nonzero inputs (states held: the inputs move between gets, no step).
 * Usage: test_fmu_derivatives <binary> <modelDescription.xml> <outputs,...> <inputs,...> */
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fmu_harness.h"

enum { MAX_PORTS = 8 };

typedef struct {
    const char *names[MAX_PORTS];
    fmi2ValueReference vr[MAX_PORTS];
    size_t n;
    char text[256];
} port_list;

static void parse_ports(const test_fmu *fmu, const char *comma_list, port_list *list)
{
    snprintf(list->text, sizeof list->text, "%s", comma_list);
    list->n = 0;
    for (char *name = strtok(list->text, ","); name != NULL; name = strtok(NULL, ",")) {
        CHECK(list->n < MAX_PORTS);
        list->names[list->n] = name;
        list->vr[list->n] = fmu_vr(fmu, name);
        list->n++;
    }
}

/* d output / d input by central differences; the models are at most smooth in their inputs,
 * and for the linear ones the difference is exact up to rounding. */
static double central_difference(test_fmu *fmu, fmi2Component c, const char *output,
                                 const char *input, double delta)
{
    double u = fmu_get(fmu, c, input);
    fmu_set(fmu, c, input, u + delta);
    double above = fmu_get(fmu, c, output);
    fmu_set(fmu, c, input, u - delta);
    double below = fmu_get(fmu, c, output);
    fmu_set(fmu, c, input, u);
    return (above - below) / (2.0 * delta);
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: %s <binary> <modelDescription.xml> <outputs> <inputs>\n", argv[0]);
        return 2;
    }
    test_fmu fmu;
    fmu_open(&fmu, argv[1], argv[2]);
    CHECK(strstr(fmu.description, "providesDirectionalDerivative=\"true\"") != NULL);
    fmi2GetDirectionalDerivativeTYPE *derivative =
        (fmi2GetDirectionalDerivativeTYPE *)dlsym(fmu.library, "fmi2GetDirectionalDerivative");
    CHECK(derivative != NULL);
    port_list outputs, inputs;
    parse_ports(&fmu, argv[3], &outputs);
    parse_ports(&fmu, argv[4], &inputs);

    fmi2Component c = fmu_start(&fmu, 0.0, 0.0, NULL, NULL, 0);
    for (size_t j = 0; j < inputs.n; ++j)
        fmu_set(&fmu, c, inputs.names[j], 0.3 + 0.2 * (double)j);
    CHECK_OK(fmu.do_step(c, 0.0, 0.1, fmi2False));

    double seed[MAX_PORTS] = {0}, column[MAX_PORTS], combined[MAX_PORTS], expected[MAX_PORTS] = {0};
    double all_ones[MAX_PORTS];
    for (size_t j = 0; j < inputs.n; ++j) {
        all_ones[j] = 1.0;
        seed[j] = 1.0;
        CHECK_OK(derivative(c, outputs.vr, outputs.n, inputs.vr, inputs.n, seed, column));
        seed[j] = 0.0;
        for (size_t i = 0; i < outputs.n; ++i) {
            double difference = central_difference(&fmu, c, outputs.names[i], inputs.names[j],
                                                   1e-4);
            char label[128];
            snprintf(label, sizeof label, "d %s / d %s", outputs.names[i], inputs.names[j]);
            /* 1e-4 steps of values of order 1-100: rounding of 1e-14 becomes 1e-10 */
            CHECK_NEAR(label, column[i], difference, 1e-8 * fmax(1.0, fabs(difference)));
            expected[i] += column[i];
        }
    }
    /* a seed over several knowns sums the columns */
    CHECK_OK(derivative(c, outputs.vr, outputs.n, inputs.vr, inputs.n, all_ones, combined));
    for (size_t i = 0; i < outputs.n; ++i)
        CHECK_NEAR("directional derivative along all inputs", combined[i], expected[i], 1e-13);

    /* only outputs with respect to inputs: an output as a known, and a missing reference */
    fmi2ValueReference missing = 100000;
    CHECK(derivative(c, outputs.vr, 1, outputs.vr, 1, all_ones, combined) == fmi2Error);
    CHECK(strstr(fmu.log.last_message, "is not a Real input") != NULL);
    CHECK(derivative(c, &missing, 1, inputs.vr, 1, all_ones, combined) == fmi2Error);
    CHECK(strstr(fmu.log.last_message, "unknown value reference 100000") != NULL);
    printf("refused: %s\n", fmu.log.last_message);
    fmu.free_instance(c);
    fmu_close(&fmu);
    return 0;
}
