# cmake --install: headers, the layer libraries, the `ancf` command and a CMake package, so that
# an outside project does find_package(ancf) and links ancf::ancf (every layer) or one layer
# (ancf::io, ancf::system, …). Included after the layers are defined.
include(CMakePackageConfigHelpers)

get_property(ancf_layers GLOBAL PROPERTY ANCF_LAYERS)
add_library(ancf_all INTERFACE)
add_library(ancf::ancf ALIAS ancf_all)
set_target_properties(ancf_all PROPERTIES EXPORT_NAME ancf)
target_link_libraries(ancf_all INTERFACE ${ancf_layers})

install(TARGETS ${ancf_layers} ancf_all EXPORT ancfTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS ancf RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/ancf DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

set(ANCF_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/ancf)
install(EXPORT ancfTargets NAMESPACE ancf:: DESTINATION ${ANCF_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ancfConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/ancfConfig.cmake
                              INSTALL_DESTINATION ${ANCF_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/ancfConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/ancfConfig.cmake ${PROJECT_BINARY_DIR}/ancfConfigVersion.cmake
        DESTINATION ${ANCF_CMAKE_DIR})
