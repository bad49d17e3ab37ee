# One command-line check (CTest, cmake -P): runs EXE with ARGS (a ;-list), then requires
#   - the exit status EXPECT_RC (0 computed, 1 a computation failed, 2 bad input),
#   - every string of CONTAIN (a ;-list) in stdout + stderr,
#   - every string of FILE_CONTAIN (a ;-list) in the files of OUT_DIR (JSON, CSV), and none of
#     FILE_ABSENT (a ;-list: e.g. a key followed by the JSON's null, a non-finite value),
#   - no nan/inf anywhere in the output nor in the files of OUT_DIR (if given): failures are
#     reported, never printed as non-finite numbers.
# STDOUT (optional) sends the standard output to that file instead (/dev/full: a result that
# cannot be written); CONTAIN then looks at stderr only.
# FULL (optional, a ;-list): result files made symlinks to /dev/full before the run (a file that
# opens and refuses every write: ENOSPC), their folders created.
# FSIZE (optional): the largest file the program may write [bytes] (prlimit --fsize): a write
# past it fails (EFBIG) as on a full disk, in the middle of a run.
# ECHOED (optional, a ;-list): the user's own bad values as the message quotes them
# ("--speed-rpm = nan"), left out of the nan/inf search.
# ABSENT (optional, a ;-list): strings that must not be in stdout + stderr.
# MEMORY_KB (optional): the program's address space limited to this (sh's ulimit -v): a run that
# allocates more fails (std::bad_alloc, exit 1), whatever it was asked.
foreach(f IN LISTS FULL)
  get_filename_component(folder "${f}" DIRECTORY)
  file(MAKE_DIRECTORY "${folder}")
  file(REMOVE "${f}")
  file(CREATE_LINK /dev/full "${f}" SYMBOLIC)
endforeach()
set(command ${EXE})
if(FSIZE)
  set(command prlimit --fsize=${FSIZE} ${EXE})
endif()
if(MEMORY_KB)
  set(command sh -c "ulimit -v ${MEMORY_KB} && exec \"$0\" \"$@\"" ${command})
endif()
if(STDOUT)
  execute_process(COMMAND ${command} ${ARGS} RESULT_VARIABLE rc OUTPUT_FILE ${STDOUT}
                  ERROR_VARIABLE err)
else()
  execute_process(COMMAND ${command} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
endif()
set(all "${out}${err}")
if(NOT "${rc}" STREQUAL "${EXPECT_RC}")
  message(FATAL_ERROR "exit status ${rc}, expected ${EXPECT_RC}; output:\n${all}")
endif()
foreach(piece IN LISTS CONTAIN)
  string(FIND "${all}" "${piece}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "output lacks \"${piece}\"; output:\n${all}")
  endif()
endforeach()
foreach(piece IN LISTS ABSENT)
  string(FIND "${all}" "${piece}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "output holds \"${piece}\"; output:\n${all}")
  endif()
endforeach()
set(texts "${all}")
if(OUT_DIR)
  file(GLOB files "${OUT_DIR}/*.csv" "${OUT_DIR}/*.json")
  if(NOT files)
    message(FATAL_ERROR "no result file in ${OUT_DIR}")
  endif()
  foreach(f IN LISTS files)
    file(READ "${f}" text)
    string(APPEND texts "${text}")
    string(APPEND file_texts "${text}")
    string(FIND "${text}" "epicycle" p)
    if(p EQUAL -1)
      message(FATAL_ERROR "${f} carries no provenance (program, version, back end, scene hash)")
    endif()
  endforeach()
endif()
foreach(piece IN LISTS FILE_CONTAIN)
  string(FIND "${file_texts}" "${piece}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the files of ${OUT_DIR} lack \"${piece}\"")
  endif()
endforeach()
foreach(piece IN LISTS FILE_ABSENT)
  string(FIND "${file_texts}" "${piece}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "the files of ${OUT_DIR} hold \"${piece}\"")
  endif()
endforeach()
foreach(piece IN LISTS ECHOED)
  string(REPLACE "${piece}" "" texts "${texts}")
endforeach()
string(TOLOWER "${texts}" lower)
if(lower MATCHES "(^|[^a-z_])-?(nan|inf|infinity)([^a-z_]|$)")
  message(FATAL_ERROR "a non-finite number (${CMAKE_MATCH_0}) in the output or the files:\n${all}")
endif()
message(STATUS "exit ${rc} as expected; ${all}")
