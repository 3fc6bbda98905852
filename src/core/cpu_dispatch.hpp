#pragma once
// Private helper: the one way the library runs AVX2 code while the build stays portable (x86-64
// baseline, SSE2; -march=native only on request). Three forms, one CPU check:
//
// 1. CROPSIGHT_AVX2_CLONES on a function (GCC/Clang target_clones): the compiler builds the
//    function three times, for x86-64-v4 (AVX-512), for AVX2 and for the baseline, and the
//    loader's resolver picks one when the program starts (the call costs nothing more than an
//    indirect call). Use it for one self-contained loop over plain arrays that the compiler
//    vectorises by itself (integral normals, organised edges, organised clustering, VFH bins, the
//    broccoli deprojection). Only that function and what it inlines are cloned: a function it
//    calls stays baseline. No FMA in any clone: x86-64-v4 has FMA instructions, so every
//    translation unit holding a clone is compiled with -ffp-contract=off (set in its
//    CMakeLists.txt) and a*b+c is never contracted; all clones then give the same values lane by
//    lane and results do not depend on the CPU (checked: `detect broccoli` writes the same bytes
//    with and without the AVX-512 clone, OES / ORG / FEC). The AVX-512 clone was added for
//    the OES speed: 1.05-1.07x on an AMD EPYC (Zen 4) VM and 1.03-1.15x on an Intel
//    Sapphire Rapids VM, alternating runs, docs/experiments/2026-11-22-broccoli-timing.md.
//
// 2. CROPSIGHT_TARGET_AVX2 on an explicit variant that the caller picks with
//    `if (cpu_has_avx2_fma())`: for a kernel written by hand in two shapes (GCC vector types of
//    8 lanes here, 4 in the baseline one), or one that tests and benchmarks switch off (the
//    census SGM's allow_avx2, the SVM's RBF sum). Adds POPCNT (the census SGM counts bits), no
//    FMA, for the same reason as in 1.
//
// 3. A whole translation unit's code between CROPSIGHT_AVX2_FMA_BEGIN and _END (GCC's
//    `#pragma GCC target`), its entry points picked by the caller with cpu_has_avx2_fma(): for a
//    body of many functions that only pays off compiled for AVX2 together (the GMM's EM,
//    segmentation/gmm_avx2.cpp: helpers that pass 8-lane vectors to each other, whose calling
//    convention depends on the target, and a lane count fixed at preprocessing time), which
//    target_clones, one function at a time, cannot express. Rules: the TU includes every header
//    (Eigen, the standard library) *before* BEGIN, so that templates shared with other TUs are
//    instantiated for the baseline (one instantiated inside the region and kept by the linker
//    for every caller would be SIGILL on a CPU without AVX2); everything defined inside has
//    internal linkage or a namespace of its own; a fallback for builds where
//    CROPSIGHT_HAVE_AVX2_TU is 0 (Clang has no `#pragma GCC target`). This form enables FMA:
//    its results may differ from the baseline build's in the last bits, which is why the GMM
//    test compares the two builds with a tolerance.
//
// Off x86-64 (or with another compiler) the macros expand to nothing and cpu_has_avx2_fma()
// is false, so only the baseline code runs.

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define CROPSIGHT_X86_DISPATCH 1
#if defined(__clang__) || defined(__SANITIZE_THREAD__)
// Clang 14 refuses target_clones on function templates (compute_links_impl); Clang builds the
// fuzz harnesses (fuzz/), where speed does not matter, so they get the baseline loop only.
// Under ThreadSanitizer (make tsan) the clones' ifunc resolver is instrumented and runs while
// the loader relocates, before TSan's runtime is up: SIGSEGV at start. Baseline loop there too.
#define CROPSIGHT_AVX2_CLONES
#else
#define CROPSIGHT_AVX2_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#endif
#define CROPSIGHT_TARGET_AVX2 __attribute__((target("avx2,popcnt")))
#else
#define CROPSIGHT_X86_DISPATCH 0
#define CROPSIGHT_AVX2_CLONES
#define CROPSIGHT_TARGET_AVX2
#endif

#if CROPSIGHT_X86_DISPATCH && defined(__GNUC__) && !defined(__clang__)
#define CROPSIGHT_HAVE_AVX2_TU 1
#define CROPSIGHT_AVX2_FMA_BEGIN _Pragma("GCC push_options") _Pragma("GCC target(\"avx2,fma\")")
#define CROPSIGHT_AVX2_FMA_END _Pragma("GCC pop_options")
#else
#define CROPSIGHT_HAVE_AVX2_TU 0
#endif

namespace cropsight::detail {

/// True when this CPU (and its OS, which must save the AVX registers) runs AVX2, FMA and POPCNT:
/// the one run-time check behind every hand-picked AVX2 variant (forms 2 and 3 above). Checked
/// once per process. Every CPU with AVX2 has the other two; asking for all three keeps one
/// answer for all variants. (Form 1 is resolved by the compiler's own check of AVX2.)
bool cpu_has_avx2_fma();

}  // namespace cropsight::detail
