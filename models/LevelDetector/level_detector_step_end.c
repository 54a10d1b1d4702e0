/* The LevelDetector as a tool that cannot return early builds it: mightReturnEarlyFromDoStep
 * false, the tank emptied inside the step at the threshold, and the output clock `full`
 * reported at the end of the step in which the level reached it. */
#define LEVEL_DETECTOR_EVENTS_AT_STEP_END 1
#include "level_detector.c"
