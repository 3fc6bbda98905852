#pragma once
// Internal: every header gmm_em.hpp needs. gmm_avx2.cpp includes this *before* its
// CROPSIGHT_AVX2_FMA_BEGIN (core/cpu_dispatch.hpp, form 3), so that Eigen and the standard library are compiled for the
// baseline there as everywhere else (a template instantiated inside the AVX2 region and merged
// by the linker into baseline code would be SIGILL on a CPU without AVX2).
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <new>
#include <numbers>
#include <random>
#include <vector>

#include "cropsight/segmentation/gmm.hpp"

#if defined(__SSE__)
#include <xmmintrin.h>
#endif
