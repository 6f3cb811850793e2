// Internal to the solvers layer: IDA's vector operations compiled with the project.
//
// Why: Debian's SUNDIALS 6.4.1 (libsundials-dev) is built without optimization — its serial
// N_Vector kernels run at -O0 (N_VWSqrSumMaskLocal_Serial keeps every operand on the stack:
// ≈ 29 instructions per element). On the benchmark pendulum (258 unknowns, BDF order ≤ 2) those
// kernels were about 60 % of all instructions of an IDA run (callgrind; studies/README.md,
// issue 20). IDA reaches all vector work through the ops table of its vectors, which every clone
// copies, so replacing the entries of the first vector gives IDA compiled kernels everywhere.
//
// Same numbers: every operation does, element by element, the floating-point operations of
// SUNDIALS' nvector_serial.c in the same order (including its special cases of N_VLinearSum:
// a = ±1, b = ±1, a = ±b, z aliasing x or y, which round differently), reductions accumulate
// sequentially from element 0; the result is bit-identical (test_ida_vector_ops compares each
// operation with SUNDIALS' own). The fused and vector-array operations IDA uses are provided as
// single passes over the elements.
#pragma once

#include <sundials/sundials_nvector.h>

namespace ancf::detail {

/// Replace the arithmetic operations of the serial vector `v` (N_VNew_Serial) by the project's
/// compiled ones, and enable the fused and vector-array operations IDA calls. Vectors cloned
/// from `v` afterwards inherit them. Precondition: v is a serial N_Vector.
void use_compiled_serial_ops(N_Vector v);

}  // namespace ancf::detail
