# Install rules, the package config for find_package(cropsight CONFIG), and the Debian package.
#
#   cmake --install build --prefix /opt/cropsight     (or: make install PREFIX=/opt/cropsight)
#   PREFIX/bin/cropsight, PREFIX/bin/cropsight_<crop>_node     the CLI and the ROS 1 nodes
#   PREFIX/lib/libcropsight_nn_torch.so                        the libtorch plugin (dlopen'ed)
#   PREFIX/lib/libcropsight_<module>.a, PREFIX/include/cropsight/   the library
#   PREFIX/lib/cmake/cropsight/                                find_package(cropsight CONFIG)
#   PREFIX/share/cropsight/{configs,models}                    presets and shipped models
#   PREFIX/share/cropsight/ros/cropsight/                      the ROS package (package.xml, launch/, nodes)
#   PREFIX/share/doc/cropsight/                                the manual (README, docs/)
#
# Everything is found relative to the program (core/install_paths.hpp), so the prefix can be
# copied anywhere; no file installed holds a path of the build machine (tests/install checks).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The build tree mirrors the install's share/cropsight, so that bin/cropsight finds its presets and
# models the same way in both (links to the source folders: edits show without a rebuild).
file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/share/cropsight)
foreach(d configs models)
  file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${d} ${PROJECT_BINARY_DIR}/share/cropsight/${d} SYMBOLIC)
endforeach()

# Installed with lib/, not lib/x86_64-linux-gnu: the programs find their plugin in ../lib.
set(cropsight_lib lib)
install(TARGETS cropsight RUNTIME DESTINATION bin COMPONENT cli)
if(TARGET cropsight_nn_torch)
  install(TARGETS cropsight_nn_torch LIBRARY DESTINATION ${cropsight_lib} COMPONENT cli)
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/configs/ DESTINATION share/cropsight/configs COMPONENT cli)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/models/ DESTINATION share/cropsight/models COMPONENT cli)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION share/doc/cropsight COMPONENT cli)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION share/doc/cropsight/docs COMPONENT cli)

# The library: the module archives, their headers, and the interface targets that carry their
# Debian dependencies (PCL, nanoflann, libsvm, XGBoost).
set(cropsight_export_targets cropsight_all)
foreach(m IN LISTS CROPSIGHT_MODULES)
  if(TARGET cropsight_${m})
    list(APPEND cropsight_export_targets cropsight_${m})
    set_target_properties(cropsight_${m} PROPERTIES EXPORT_NAME ${m})
  endif()
endforeach()
foreach(dep pcl nanoflann libsvm xgboost)
  list(APPEND cropsight_export_targets cropsight_${dep})
  set_target_properties(cropsight_${dep} PROPERTIES EXPORT_NAME deps_${dep})
endforeach()
set_target_properties(cropsight_all PROPERTIES EXPORT_NAME cropsight)
install(TARGETS ${cropsight_export_targets} EXPORT cropsightTargets
        ARCHIVE DESTINATION ${cropsight_lib} COMPONENT dev
        INCLUDES DESTINATION include)
# The studio's headers stay out: its library is linked into the CLI only (src/studio/CMakeLists.txt).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/cropsight DESTINATION include COMPONENT dev PATTERN studio EXCLUDE)
install(EXPORT cropsightTargets NAMESPACE cropsight:: DESTINATION ${cropsight_lib}/cmake/cropsight COMPONENT dev)
set(CROPSIGHT_INSTALL_DATA_DIR share/cropsight)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/cropsightConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/cropsightConfig.cmake
                              INSTALL_DESTINATION ${cropsight_lib}/cmake/cropsight
                              PATH_VARS CROPSIGHT_INSTALL_DATA_DIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/cropsightConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/cropsightConfig.cmake ${PROJECT_BINARY_DIR}/cropsightConfigVersion.cmake
        DESTINATION ${cropsight_lib}/cmake/cropsight COMPONENT dev)

# `make package`: one .deb whose dependencies are the Debian packages scripts/install-deps.sh
# installs for running (the -dev packages the library's headers need come with the dev part).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME cropsight)
set(CPACK_PACKAGE_VENDOR "cropsight")
set(CPACK_PACKAGE_CONTACT "cropsight developers <cropsight@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "3D perception for harvesting and weeding robots: CLI, ROS 1 nodes, C++ library")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr/local)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "libopencv-dev, libopencv-dnn-dev, libpcl-dev, libeigen3-dev, libnanoflann-dev, libtbb-dev, libsvm-dev, libyaml-cpp-dev, nlohmann-json3-dev, libspdlog-dev, libfmt-dev, libtinyxml2-dev, libproj-dev, libtorch-dev, libxgboost-dev, libopenblas0-pthread, libroscpp-dev, librosbag-storage-dev")
# The Python package (python/CMakeLists.txt) runs on Debian's interpreter and numpy.
if(CROPSIGHT_HAS_PYTHON)
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", python3 (>= ${CROPSIGHT_PYTHON_VERSION}), python3-numpy")
endif()
include(CPack)
