// The lane kernels compiled for AVX2 (this file alone gets -mavx2).
#include "relax_lanes.h"

#define PHYS_LANE_ISA avx2
#include "relax_lanes_kernels.inc"
