# uPlot from the npm registry, pinned by cmake/uplot/package-lock.json, installed once per build
# with `npm ci` in a copy of cmake/uplot inside the build directory (the source tree stays clean).
# The eval report (client/report) and the dashboard (server/http) both embed it:
#   STRATA_UPLOT_DIR    node_modules/uplot of the build
#   STRATA_UPLOT_FILES  its package.json and dist files (DEPENDS of an embedding command)
#   strata_uplot        the target that installs it (add_dependencies of an embedding library)
#   strata_embed_assets(OUT file.cpp HEADER "x/y.h" NAMESPACE ns ASSETS name path ...)
#                       a custom command writing file.cpp: each asset as a byte array behind
#                       `std::string_view name()`, plus `uplot_version()`.
find_program(NPM npm REQUIRED)

set(STRATA_UPLOT_BIN ${CMAKE_BINARY_DIR}/uplot)
set(STRATA_UPLOT_DIR ${STRATA_UPLOT_BIN}/node_modules/uplot)
set(STRATA_UPLOT_FILES ${STRATA_UPLOT_DIR}/package.json ${STRATA_UPLOT_DIR}/dist/uPlot.iife.min.js
                       ${STRATA_UPLOT_DIR}/dist/uPlot.min.css)
file(MAKE_DIRECTORY ${STRATA_UPLOT_BIN})
# npm ci gives the extracted files the tarball's 1985 timestamps, hence the touch: without it the
# outputs would look older than package-lock.json and the command would run on every build.
add_custom_command(
  OUTPUT ${STRATA_UPLOT_FILES}
  COMMAND ${CMAKE_COMMAND} -E copy_if_different ${PROJECT_SOURCE_DIR}/cmake/uplot/package.json
          ${PROJECT_SOURCE_DIR}/cmake/uplot/package-lock.json ${STRATA_UPLOT_BIN}
  COMMAND ${NPM} ci --no-audit --no-fund --ignore-scripts
  COMMAND ${CMAKE_COMMAND} -E touch ${STRATA_UPLOT_FILES}
  WORKING_DIRECTORY ${STRATA_UPLOT_BIN}
  DEPENDS ${PROJECT_SOURCE_DIR}/cmake/uplot/package.json ${PROJECT_SOURCE_DIR}/cmake/uplot/package-lock.json
  COMMENT "npm ci (uPlot)"
  VERBATIM)
add_custom_target(strata_uplot DEPENDS ${STRATA_UPLOT_FILES})

function(strata_embed_assets)
  cmake_parse_arguments(E "" "OUT;HEADER;NAMESPACE" "ASSETS" ${ARGN})
  set(paths "")
  foreach(item IN LISTS E_ASSETS)
    if(IS_ABSOLUTE "${item}")
      list(APPEND paths "${item}")
    endif()
  endforeach()
  string(REPLACE ";" "|" assets "${E_ASSETS}")
  add_custom_command(
    OUTPUT ${E_OUT}
    COMMAND ${CMAKE_COMMAND} -DOUT=${E_OUT} -DHEADER=${E_HEADER} -DNAMESPACE=${E_NAMESPACE} -DUPLOT_DIR=${STRATA_UPLOT_DIR}
            "-DASSETS=${assets}" -P ${PROJECT_SOURCE_DIR}/cmake/embed_assets.cmake
    DEPENDS ${PROJECT_SOURCE_DIR}/cmake/embed_assets.cmake ${STRATA_UPLOT_FILES} ${paths}
    COMMENT "Embedding web assets into ${E_OUT}"
    VERBATIM)
endfunction()
