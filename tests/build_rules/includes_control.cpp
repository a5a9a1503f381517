#include "motion/motion.h"  // compiles: the control for the probes beside it
int probe() { return motionstyle::Motion{}.frameCount(); }
