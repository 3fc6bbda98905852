# cropsight_module(NAME <m> [SUBDIRS <folders>...] [DEPS <public targets>...] [PRIVATE_DEPS <targets>...]
#                  [TEST_DEPS <targets>...] [THREADED_OPENCV_TESTS])
#
# Builds library cropsight_<m> from src/<m>/*.cpp and src/<m>/<subdir>/*.cpp for each SUBDIRS
# folder (public headers in include/cropsight/<m>/[<subdir>/]), and, when tests/<m>/ (or
# tests/<m>/<subdir>/) holds *.cpp files, the GoogleTest executable test_<m> registered with ctest.
# Files are globbed so that adding a source file needs no edit here. Sub-folders are listed, not
# globbed recursively, because some modules keep a separately built part in a sub-folder
# (src/nn/torch/ is the libtorch plugin, never linked into cropsight_nn).
# Test executables compile as unity builds (CMake UNITY_BUILD, batches of
# CROPSIGHT_UNITY_BATCH files): every test file includes GoogleTest and most include Eigen, PCL or
# OpenCV, whose parsing dominated their compile time; one batch parses them once. Measured on
# tests/geometry (7 files, PCL): 67 s of CPU compiled one by one, 33 s as one unity file.
# The module libraries compile as unity batches too (CROPSIGHT_UNITY_LIBS; 135 files took 480 s of
# CPU one by one). CMake leaves out of a batch every file with its own COMPILE_OPTIONS (the -O3 hot
# kernels), and the modules mark the files whose pragmas, macros or AVX2 regions must not reach a
# neighbour with SKIP_UNITY_BUILD_INCLUSION (segmentation: the GMM's EM; stereo: the census SGM;
# learning: the SVM's RBF sum), so the benchmarked code generation of every hot path is unchanged.
# In a batch, file-local names share one translation unit: a helper written twice in a module does
# not compile, which is how the report's four number formatters and the simulators' angle
# constants became one each. -DCROPSIGHT_UNITY_TESTS=OFF / -DCROPSIGHT_UNITY_LIBS=OFF compile
# files one by one (a file that only compiles inside a batch is a bug that build shows).
option(CROPSIGHT_UNITY_TESTS "Compile each test executable as unity batches" ON)
option(CROPSIGHT_UNITY_LIBS "Compile each module library as unity batches" ON)
set(CROPSIGHT_UNITY_BATCH 8 CACHE STRING "Test files per unity batch")
function(cropsight_unity_tests target)
  if(CROPSIGHT_UNITY_TESTS)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${CROPSIGHT_UNITY_BATCH})
    # In a batch each test file is #included, so GCC takes a fixture in an anonymous namespace for
    # one declared in a header (-Wsubobject-linkage); in a unity source that cannot break the ODR.
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      target_compile_options(${target} PRIVATE -Wno-subobject-linkage)
    endif()
  endif()
endfunction()

function(cropsight_module)
  cmake_parse_arguments(M "THREADED_OPENCV_TESTS" "NAME" "SUBDIRS;DEPS;PRIVATE_DEPS;TEST_DEPS;PCH" ${ARGN})
  set(src_globs ${PROJECT_SOURCE_DIR}/src/${M_NAME}/*.cpp)
  set(test_globs ${PROJECT_SOURCE_DIR}/tests/${M_NAME}/*.cpp)
  foreach(d IN LISTS M_SUBDIRS)
    list(APPEND src_globs ${PROJECT_SOURCE_DIR}/src/${M_NAME}/${d}/*.cpp)
    list(APPEND test_globs ${PROJECT_SOURCE_DIR}/tests/${M_NAME}/${d}/*.cpp)
  endforeach()
  file(GLOB srcs CONFIGURE_DEPENDS ${src_globs})
  set(lib cropsight_${M_NAME})
  if(NOT srcs)
    # A module with headers only (or not started yet) is an interface library.
    add_library(${lib} INTERFACE)
    target_include_directories(${lib} INTERFACE $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:include>)
    target_link_libraries(${lib} INTERFACE ${M_DEPS})
    add_library(cropsight::${M_NAME} ALIAS ${lib})
    return()
  endif()
  add_library(${lib} STATIC ${srcs})
  if(CROPSIGHT_UNITY_LIBS)
    set_target_properties(${lib} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${CROPSIGHT_UNITY_BATCH})
    # As for the tests: a source #included into a batch after another one is taken for a header, so
    # a pimpl holding a type of its own file's anonymous namespace warns (-Wsubobject-linkage;
    # geometry/knn_normals.cpp whenever a file sorts before it in its batch). No ODR risk there.
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      target_compile_options(${lib} PRIVATE -Wno-subobject-linkage)
    endif()
  endif()
  # The installed headers are PREFIX/include (cmake/Install.cmake); no library is compiled with a path
  # of the source tree (core/install_paths.hpp says how an install finds its data).
  target_include_directories(${lib} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:include>
                                    PRIVATE ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(${lib} PUBLIC ${M_DEPS} PRIVATE ${M_PRIVATE_DEPS})
  if(M_PCH)
    target_precompile_headers(${lib} PRIVATE ${M_PCH})
  endif()
  add_library(cropsight::${M_NAME} ALIAS ${lib})

  if(CROPSIGHT_BUILD_TESTS)
    file(GLOB tsrcs CONFIGURE_DEPENDS ${test_globs})
    if(tsrcs)
      add_executable(test_${M_NAME} ${tsrcs})
      target_include_directories(test_${M_NAME} PRIVATE ${PROJECT_SOURCE_DIR}/tests ${PROJECT_SOURCE_DIR}/src)
      target_link_libraries(test_${M_NAME} PRIVATE ${lib} ${M_PRIVATE_DEPS} ${M_TEST_DEPS} cropsight_testing GTest::gtest GTest::gtest_main)
      target_compile_definitions(test_${M_NAME} PRIVATE
        CROPSIGHT_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
        CROPSIGHT_SHARED_DATA_DIR="${PROJECT_SOURCE_DIR}/../shared/data"
        CROPSIGHT_CLI="${PROJECT_BINARY_DIR}/bin/cropsight")
      cropsight_unity_tests(test_${M_NAME})
      if(CROPSIGHT_SANITIZE AND M_THREADED_OPENCV_TESTS)
        # Tests that run OpenCV on several threads: tests/lsan.supp names OpenCV frames (see
        # CROPSIGHT_LSAN_FULL_UNWIND in the top CMakeLists.txt).
        gtest_discover_tests(test_${M_NAME} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS ${M_NAME}
                             ENVIRONMENT "${CROPSIGHT_LSAN_FULL_UNWIND}")
      else()
        gtest_discover_tests(test_${M_NAME} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS ${M_NAME})
      endif()
    endif()
  endif()
endfunction()
