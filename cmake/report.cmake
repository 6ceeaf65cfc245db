# The browser report (docs/report.md): report/src bundled by esbuild (node) into one script,
# embedded with uPlot's CSS into the program as a generated source. Options turn parts off,
# not on: the report is built whenever node and report/node_modules (scripts/setup.sh runs
# npm ci there) are present; -DCHASLES_BUILD_REPORT=OFF leaves it out. Without it the
# program's --html and `report` say that this build has no report.
option(CHASLES_BUILD_REPORT "Build the browser report when node and report/node_modules exist"
       ON)
set(CHASLES_REPORT_DIR ${PROJECT_SOURCE_DIR}/report)
find_program(CHASLES_NODE node)
set(CHASLES_HAVE_REPORT OFF)
if(CHASLES_BUILD_REPORT)
  if(CHASLES_NODE AND EXISTS ${CHASLES_REPORT_DIR}/node_modules/esbuild/package.json
     AND EXISTS ${CHASLES_REPORT_DIR}/node_modules/three/package.json
     AND EXISTS ${CHASLES_REPORT_DIR}/node_modules/uplot/package.json)
    set(CHASLES_HAVE_REPORT ON)
  else()
    message(STATUS "chasles: node or report/node_modules not found (scripts/setup.sh runs npm ci "
                   "in report/); the program is built without the browser report")
  endif()
endif()

# chasles_report_source(VAR): the generated source defining the embedded script and style.
function(chasles_report_source var)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/report_bundle.cpp)
  set(embed ${PROJECT_SOURCE_DIR}/cmake/embed_report.cmake)
  if(CHASLES_HAVE_REPORT)
    file(GLOB sources CONFIGURE_DEPENDS ${CHASLES_REPORT_DIR}/src/*.js
         ${CHASLES_REPORT_DIR}/src/*.css)
    set(js ${CMAKE_CURRENT_BINARY_DIR}/report/report.js)
    set(css ${CMAKE_CURRENT_BINARY_DIR}/report/report.css)
    add_custom_command(
      OUTPUT ${js} ${css}
      COMMAND ${CHASLES_NODE} ${CHASLES_REPORT_DIR}/build.mjs ${js} ${css}
      DEPENDS ${sources} ${CHASLES_REPORT_DIR}/build.mjs ${CHASLES_REPORT_DIR}/package-lock.json
      WORKING_DIRECTORY ${CHASLES_REPORT_DIR}
      COMMENT "Bundling the browser report (esbuild)"
      VERBATIM)
    add_custom_command(
      OUTPUT ${out}
      COMMAND ${CMAKE_COMMAND} -DSCRIPT=${js} -DSTYLE=${css} -DOUTPUT=${out} -P ${embed}
      DEPENDS ${js} ${css} ${embed}
      COMMENT "Embedding the browser report"
      VERBATIM)
  else()
    add_custom_command(
      OUTPUT ${out}
      COMMAND ${CMAKE_COMMAND} -DOUTPUT=${out} -P ${embed}
      DEPENDS ${embed}
      VERBATIM)
  endif()
  set(${var} ${out} PARENT_SCOPE)
endfunction()
