# CTest "python: EPICYCLE_WITH_PYTHON=ON without pybind11 fails the configure step" (cmake -P):
# configures SOURCE in WORK with pybind11 hidden (CMAKE_DISABLE_FIND_PACKAGE_pybind11); asked for
# explicitly, the module must stop the configure step with its message; left to its default, the
# configure step must pass with the module OFF.
foreach(v SOURCE WORK PYTHON)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "configure_without_pybind11.cmake: -D${v}=... is required")
  endif()
endforeach()
set(common -DCMAKE_DISABLE_FIND_PACKAGE_pybind11=ON -DEPICYCLE_BUILD_TESTS=OFF
           -DEPICYCLE_BUILD_BENCHMARKS=OFF -DPython3_EXECUTABLE=${PYTHON})
file(REMOVE_RECURSE "${WORK}")
execute_process(COMMAND ${CMAKE_COMMAND} -S "${SOURCE}" -B "${WORK}/on" -DEPICYCLE_WITH_PYTHON=ON
                        ${common}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "EPICYCLE_WITH_PYTHON is ON but Python 3 \\(python3-dev\\) or pybind11")
  message(FATAL_ERROR "EPICYCLE_WITH_PYTHON=ON without pybind11: exit ${rc}, not the message:\n${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S "${SOURCE}" -B "${WORK}/default" ${common}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(STRINGS "${WORK}/default/CMakeCache.txt" option REGEX "^EPICYCLE_WITH_PYTHON:")
if(NOT rc EQUAL 0 OR NOT option STREQUAL "EPICYCLE_WITH_PYTHON:BOOL=OFF")
  message(FATAL_ERROR "default without pybind11: exit ${rc}, ${option}\n${err}")
endif()
file(REMOVE_RECURSE "${WORK}")
