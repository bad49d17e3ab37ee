# The install test (cmake -P): installs the build tree BUILD into WORK/prefix, checks the installed
# program and package files, configures the consumer project against the prefix alone, builds it
# and runs it on SCENE (CACHE: the influence-table cache).
foreach(v BUILD SOURCE WORK SCENE CACHE)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "install_test.cmake: -D${v}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK}")
set(prefix "${WORK}/prefix")
function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGV}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
run(${CMAKE_COMMAND} --install "${BUILD}" --prefix "${prefix}")
foreach(f bin/epicycle include/epicycle/config.h include/epicycle/transmission/scene.hpp
          include/epicycle/solvers/contact_problem.hpp include/epicycle/studies/study.hpp
          lib/cmake/epicycle/epicycleConfig.cmake
          lib/cmake/epicycle/epicycleTargets.cmake)
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
# The Python package (a build with EPICYCLE_WITH_PYTHON): imported from the prefix alone.
if(PYTHON AND PYTHON_DIR)
  set(site "${PYTHON_DIR}")
  if(NOT IS_ABSOLUTE "${site}")
    set(site "${prefix}/${site}")
  endif()
  run(${CMAKE_COMMAND} -E env "PYTHONPATH=${site}" PYTHONDONTWRITEBYTECODE=1 ${PYTHON}
      "${SOURCE}/verification/install/python_import.py" "${prefix}")
  message(STATUS "installed Python package: ${last_output}")
endif()
run("${prefix}/bin/epicycle" --version)
message(STATUS "installed program: ${last_output}")
set(launcher)
find_program(ccache ccache)
if(ccache)
  set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${ccache})
endif()
# A sanitizer build installs instrumented static libraries: the consumer links the same runtime,
# so it is built by the same compiler (clang's and gcc's sanitizer runtimes differ).
set(flags)
if(CXX)
  list(APPEND flags "-DCMAKE_CXX_COMPILER=${CXX}")
endif()
if(SANITIZE)
  list(APPEND flags "-DCMAKE_CXX_FLAGS=-fsanitize=${SANITIZE}"
                    "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=${SANITIZE}")
endif()
run(${CMAKE_COMMAND} -S "${SOURCE}/verification/install" -B "${WORK}/build"
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}" ${launcher} ${flags})
run(${CMAKE_COMMAND} --build "${WORK}/build" -j 2)
run("${WORK}/build/consumer" "${SCENE}" "${CACHE}")
message(STATUS "consumer: ${last_output}")
