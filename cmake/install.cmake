# `cmake --install build --prefix P`: the public headers, the static libraries, the `bezinv`
# command, and a CMake package so a consumer can write
#   find_package(bezinv CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE bezinv::engine)
include(CMakePackageConfigHelpers)

set(BEZINV_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/bezinv)

# The engine's headers only: none of them includes the kernels' (kernels/CMakeLists.txt).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/include/bezinv DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.hpp")
# bezinv_kernels is installed (and exported) because the static engine needs it at link time.
install(TARGETS bezinv_engine bezinv_kernels EXPORT bezinv-targets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS bezinv RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

install(EXPORT bezinv-targets NAMESPACE bezinv:: DESTINATION ${BEZINV_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/bezinv-config.cmake.in
                              ${PROJECT_BINARY_DIR}/bezinv-config.cmake INSTALL_DESTINATION ${BEZINV_CMAKE_DIR})
# SameMajorVersion: a request for 0.1 accepts any 0.x at least 0.1, and a request for 1.0 will not
# accept 2.0 -- the major version is what changes when the API breaks. AnyNewerVersion would
# promise that every later major version still builds the consumer, which nothing here checks.
# Not ARCH_INDEPENDENT: the package holds compiled static libraries for one pointer size.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/bezinv-config-version.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/bezinv-config.cmake ${PROJECT_BINARY_DIR}/bezinv-config-version.cmake
              ${CMAKE_CURRENT_LIST_DIR}/FindGMP.cmake
        DESTINATION ${BEZINV_CMAKE_DIR})
