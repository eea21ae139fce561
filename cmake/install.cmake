# Installation and the CMake package: `cmake --install build --prefix P` puts the headers in
# P/include, the libraries in P/lib, gsse-mesh in P/bin and the package in P/lib/cmake/gsse, so that
#   find_package(gsse CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE gsse::mesher)   # or gsse::core for the topology core only
# works (tests/install checks it with a consumer project against an install tree).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# gsse::mesher: everything a program that meshes a file needs (pipeline, I/O, PLC tools, rules)
add_library(gsse_mesher INTERFACE)
add_library(gsse::mesher ALIAS gsse_mesher)
target_link_libraries(gsse_mesher INTERFACE gsse_pipeline gsse_io gsse_plc gsse_rules)

set(_gsse_targets gsse_core gsse_rules gsse_io gsse_plc gsse_conformer gsse_front gsse_verify gsse_sizing gsse_location gsse_placement gsse_refinement gsse_pipeline gsse_mesher)
foreach(t IN LISTS _gsse_targets)
  string(REPLACE "gsse_" "" _name ${t})
  set_target_properties(${t} PROPERTIES EXPORT_NAME ${_name})
endforeach()
install(TARGETS ${_gsse_targets} EXPORT gsseTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS gsse-mesh RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(d gsse/include rules/include modules/io/include modules/plc/include modules/conformer/include
          modules/front/include modules/verify/include modules/sizing/include modules/location/include modules/placement/include modules/refinement/include
          modules/pipeline/include)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${d}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/gsse)
install(EXPORT gsseTargets NAMESPACE gsse:: FILE gsseTargets.cmake DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/gsse)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/gsseConfig.cmake.in ${PROJECT_BINARY_DIR}/gsseConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/gsse)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/gsseConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/gsseConfig.cmake ${PROJECT_BINARY_DIR}/gsseConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/gsse)
