# Generates the OpenGL 3.3 core loader with Debian's python3-glad at build time.
# /usr/bin/python3 on purpose: glad is installed for Debian's interpreter, not for any other
# python on PATH. --reproducible uses the specification bundled with the package, so the build
# needs no network.
set(GLAD_PYTHON /usr/bin/python3)
set(GLAD_OUT "${CMAKE_BINARY_DIR}/glad")
set(GLAD_SOURCES "${GLAD_OUT}/src/gl.c")
set(GLAD_HEADERS "${GLAD_OUT}/include/glad/gl.h" "${GLAD_OUT}/include/KHR/khrplatform.h")

execute_process(COMMAND ${GLAD_PYTHON} -c "import glad" RESULT_VARIABLE glad_missing
                OUTPUT_QUIET ERROR_QUIET)
if(glad_missing)
  message(FATAL_ERROR "glad is not importable by ${GLAD_PYTHON}; run scripts/install-deps "
                      "(Debian package python3-glad)")
endif()

add_custom_command(
  OUTPUT ${GLAD_SOURCES} ${GLAD_HEADERS}
  COMMAND ${GLAD_PYTHON} -m glad --api gl:core=3.3 --reproducible --quiet --out-path ${GLAD_OUT} c
  COMMENT "Generating the OpenGL 3.3 core loader with glad"
  VERBATIM)

add_library(glad STATIC ${GLAD_SOURCES} ${GLAD_HEADERS})
target_include_directories(glad SYSTEM PUBLIC "${GLAD_OUT}/include")
target_link_libraries(glad PUBLIC ${CMAKE_DL_LIBS})
set_target_properties(glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
