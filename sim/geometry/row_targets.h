#pragma once
// The row kernels (axial_row.cpp, cross_row.cpp, swept_rows.cpp) are written to be
// vectorised. Release builds clone them: one clone for AVX2 machines (four lines per
// instruction) and one for any x86-64, chosen when the program loads. No FMA: it
// would round differently from the line-by-line forms they must match to the bit.
#if defined(MDHD_ROW_CLONES) && defined(__x86_64__)
#define MDHD_ROW_TARGETS __attribute__((target_clones("avx2", "default")))
#else
#define MDHD_ROW_TARGETS
#endif
