// The lane kernels compiled for the x86-64 baseline (SSE2).
#include "relax_lanes.h"

#define PHYS_LANE_ISA baseline
#include "relax_lanes_kernels.inc"
