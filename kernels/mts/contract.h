// Contraction as the variant's CONTRACT says: 1, the compiler may fuse a*b+c; 0, every operation
// rounds on its own. Included first by every program of the emulated pipeline (kernels/mts.cl,
// kernels/mts_setup.cl, kernels/bias.cl), so the pragma covers all of its code, the storage
// formats' included.
#if CONTRACT
#pragma OPENCL FP_CONTRACT ON
#else
#pragma OPENCL FP_CONTRACT OFF
#endif
