#pragma once
// How large MuJoCo 2.2.2's mjData can be made for a model. 2.2.2 allocates everything a step
// may need up front, in one buffer per mjData, from two sizes in the model: njmax (constraint
// rows) and nconmax (contacts). Among its arrays are efc_AR (njmax x njmax doubles, and as many
// ints for its column indices) and efc_J and efc_JT (njmax x nv each, with int indices), so the
// buffer grows as 12 njmax^2 + 24 njmax nv bytes. Its size is an int (mjData::nbuffer, bytes):
// above 2^31 - 1 it cannot be made at all, whatever the memory ("could not create mjData").
// Newer MuJoCo sizes an arena by memory instead; Debian 12 ships 2.2.2.
//
// So the adapter compiles the model with tiny sizes, then asks these functions for the largest
// njmax whose buffer fits, and sets njmax, nconmax and nstack on the compiled model before
// mj_makeData: the exact layout (mjxmacro.h) instead of a guess.
#include <cstdint>

#include <mujoco/mujoco.h>

namespace lab::peers::mujoco_size {

/// The largest buffer made here (bytes): 2^31 - 1 less 64 MB for what the estimate does not see.
inline constexpr double kMaxBufferBytes = 2147483647.0 - 64.0 * 1024 * 1024;

/// Bytes of mjData's main buffer for `model` with njmax rows and nconmax contacts: every array
/// of MJDATA_POINTERS, each rounded up to 8 bytes as mj_makeData lays them out.
double bufferBytes(const mjModel& model, int njmax, int nconmax);

/// The largest njmax (<= want) whose buffer fits kMaxBufferBytes with nconmax contacts; 0 if
/// none does.
int largestRows(const mjModel& model, int nconmax, int want);

/// The mjtNums of stack a step of `model` may use with njmax rows: 6 nv^2 and some per row and
/// dof, above the 3 to 5 nv^2 measured on the ragdoll piles (mujoco_size.cpp). The stack is
/// allocated whole but only what a step uses is ever touched.
std::int64_t stackFor(const mjModel& model, int njmax);

}  // namespace lab::peers::mujoco_size
