# Every dependency comes from a Debian package (scripts/install-deps.sh).
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(spdlog REQUIRED)
find_package(fmt REQUIRED)
find_package(TBB REQUIRED)
find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc imgcodecs calib3d video ml dnn)
find_package(Threads REQUIRED)
# Pascal VOC XML annotations (potato detection): used only inside src/io/voc.cpp.
find_package(tinyxml2 REQUIRED)
# zlib: inflating the deflated entries of libtorch archives to check their CRC-32 (src/io/zip_check.cpp).
find_package(ZLIB REQUIRED)
# PROJ: field frame <-> WGS84 for geo-referenced maps (io/geo_origin.hpp)
find_package(PROJ REQUIRED CONFIG)

# PCL: only the component libraries we use, found directly. PCL's own CMake config pulls in
# VTK (and through it MPI and Qt), which we never use and which slows configuration down.
find_path(PCL_INCLUDE_DIR pcl/point_types.h PATH_SUFFIXES pcl-1.13 pcl-1.14 pcl-1.12 REQUIRED)
set(CROPSIGHT_PCL_COMPONENTS common io io_ply features search kdtree segmentation filters surface octree sample_consensus)
set(CROPSIGHT_PCL_LIBS)
foreach(c IN LISTS CROPSIGHT_PCL_COMPONENTS)
  find_library(PCL_${c}_LIBRARY NAMES pcl_${c} REQUIRED)
  list(APPEND CROPSIGHT_PCL_LIBS ${PCL_${c}_LIBRARY})
endforeach()
find_package(Boost REQUIRED COMPONENTS filesystem iostreams)
find_library(LZ4_LIBRARY NAMES lz4 REQUIRED)
find_path(FLANN_INCLUDE_DIR flann/flann.hpp REQUIRED)
find_library(FLANN_LIBRARY NAMES flann_cpp REQUIRED)
find_library(QHULL_LIBRARY NAMES qhull_r REQUIRED)
add_library(cropsight_pcl INTERFACE)
target_include_directories(cropsight_pcl SYSTEM INTERFACE ${PCL_INCLUDE_DIR} ${FLANN_INCLUDE_DIR})
target_link_libraries(cropsight_pcl INTERFACE ${CROPSIGHT_PCL_LIBS} ${FLANN_LIBRARY} ${QHULL_LIBRARY} ${LZ4_LIBRARY}
  Boost::filesystem Boost::iostreams Eigen3::Eigen)

# nanoflann is header-only.
find_path(NANOFLANN_INCLUDE_DIR nanoflann.hpp REQUIRED)
add_library(cropsight_nanoflann INTERFACE)
target_include_directories(cropsight_nanoflann SYSTEM INTERFACE ${NANOFLANN_INCLUDE_DIR})

# libsvm ships no CMake config.
find_path(LIBSVM_INCLUDE_DIR NAMES libsvm/svm.h REQUIRED)
find_library(LIBSVM_LIBRARY NAMES svm REQUIRED)
add_library(cropsight_libsvm INTERFACE)
target_include_directories(cropsight_libsvm SYSTEM INTERFACE ${LIBSVM_INCLUDE_DIR})
target_link_libraries(cropsight_libsvm INTERFACE ${LIBSVM_LIBRARY})

if(CROPSIGHT_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(CROPSIGHT_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

# Grape pipeline: XGBoost (libxgboost-dev) for the classical per-point model, used only
# inside src/learning/gbdt.cpp; libtorch (libtorch-dev) for the point networks, used only inside
# src/nn/*.cpp (never in public headers: TorchConfig adds heavy include paths and flags).
# Debian's XGBoost CMake config references a /usr/bin/xgboost that the -dev package does not
# ship, so the library is found directly.
find_path(XGBOOST_INCLUDE_DIR xgboost/c_api.h REQUIRED)
find_library(XGBOOST_LIBRARY NAMES xgboost REQUIRED)
add_library(cropsight_xgboost INTERFACE)
target_include_directories(cropsight_xgboost SYSTEM INTERFACE ${XGBOOST_INCLUDE_DIR})
target_link_libraries(cropsight_xgboost INTERFACE ${XGBOOST_LIBRARY})
find_package(Torch REQUIRED CONFIG PATHS /usr/lib/x86_64-linux-gnu/cmake/Torch /usr/share/cmake/Torch)
add_library(cropsight_torch INTERFACE)
target_link_libraries(cropsight_torch INTERFACE ${TORCH_LIBRARIES})
target_include_directories(cropsight_torch SYSTEM INTERFACE ${TORCH_INCLUDE_DIRS})
