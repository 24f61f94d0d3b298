# What `cmake --install BUILD --prefix PREFIX` puts where (GNU layout):
#   bin/beamid                              the program
#   lib/libbeamid_*.a                       the libraries, one per folder
#   include/beamid/{hb,signal,solver}/…h    their headers, included as in the sources ("hb/scenario.h")
#   lib/cmake/beamid/                       find_package(beamid): targets beamid::hb, beamid::signal,
#                                           beamid::estimation, …, beamid::solver (all of solver/)
#   share/doc/beamid/                       README.md, docs/ (the formats, the licence)
#   share/beamid/examples/                  the examples, their run.sh scripts executable
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(BEAMID_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/beamid)
set(BEAMID_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/beamid)
set(beamid_libraries beamid_hb beamid_signal beamid_estimation beamid_diagnosis beamid_live beamid_backbone
    beamid_report beamid_workflow beamid_solver)
foreach(library ${beamid_libraries})
  string(REPLACE "beamid_" "" short_name ${library})
  set_target_properties(${library} PROPERTIES EXPORT_NAME ${short_name})
endforeach()

install(TARGETS beamid RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS ${beamid_libraries} EXPORT beamidTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(folder hb signal solver)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder} DESTINATION ${BEAMID_INSTALL_INCLUDEDIR}
          FILES_MATCHING PATTERN "*.h" PATTERN "cli" EXCLUDE PATTERN "python" EXCLUDE)
endforeach()
install(EXPORT beamidTargets NAMESPACE beamid:: DESTINATION ${BEAMID_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/beamidConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/beamidConfig.cmake INSTALL_DESTINATION ${BEAMID_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/beamidConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/beamidConfig.cmake ${PROJECT_BINARY_DIR}/beamidConfigVersion.cmake
        DESTINATION ${BEAMID_INSTALL_CMAKEDIR})

install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/ DESTINATION ${CMAKE_INSTALL_DATADIR}/beamid/examples
        USE_SOURCE_PERMISSIONS)
