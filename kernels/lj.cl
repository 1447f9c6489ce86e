// The Lapidous-Jiao average error over N samples, one chunk of samples per work-item; the host
// adds the partial sums in order (compensated), so the result does not depend on scheduling.
// Specialised by -D defines for the storage format (DF_*); the buffer type and sampling are
// arguments (they pick a formula per sample, not a code path worth a program each).
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#define DF_ENABLE_FP64 1
#include "interface/lj_formulas.h"

__kernel void lj_partials(const int buffer, const int sampling, const double d, const double f,
                          const long n, const long chunk, __global double* restrict sums,
                          __global long* restrict counts) {
  const long id = get_global_id(0);
  const long first = id * chunk;
  const long last = min(first + chunk, n);
  lj_config c;
  c.buffer = buffer;
  c.sampling = sampling;
  c.d = d;
  c.f = f;
  c.n = n;
  lj_partial p;
  if (first < last) {
    p = lj_sum_range(c, DF_FORMAT_FROM_DEFINES(), first, last);
  } else {
    p.num = p.num_c = p.den = p.den_c = 0.0;
    p.infinite = p.vertex_limited = 0;
  }
  sums[4 * id + 0] = p.num;
  sums[4 * id + 1] = p.num_c;
  sums[4 * id + 2] = p.den;
  sums[4 * id + 3] = p.den_c;
  counts[2 * id + 0] = p.infinite;
  counts[2 * id + 1] = p.vertex_limited;
}
