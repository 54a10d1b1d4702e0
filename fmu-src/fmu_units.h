/* SI decomposition of the units the models use, for the UnitDefinitions of the XML. */
#ifndef SYSSIMX_FMU_UNITS_H
#define SYSSIMX_FMU_UNITS_H

typedef struct {
    const char *name;
    int kg, m, s, rad;
    double factor; /* value in SI = factor * value in this unit */
} unit_definition;

/* The definition of a unit name, or NULL when the unit is unknown (a build error). */
const unit_definition *fmu_unit(const char *name);

#endif
