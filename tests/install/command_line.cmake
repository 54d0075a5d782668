# Helpers of the scripts in this folder (cmake -P): run a command and keep what it printed.
foreach(var ${required_vars})
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "-D${var}= is required")
  endif()
endforeach()

# Runs a command that must succeed; run_output / run_log: its stdout / stderr.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "failed (${rc}): ${cmd}\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
  set(run_log "${err}" PARENT_SCOPE)
endfunction()

# Runs a command that must fail; run_log: its stderr.
function(run_failing)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "succeeded but should have failed: ${cmd}\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
  set(run_log "${err}" PARENT_SCOPE)
endfunction()

# Fails unless `text` matches the regular expression `pattern`.
function(expect_match what text pattern)
  if(NOT text MATCHES "${pattern}")
    message(FATAL_ERROR "${what}: no match for '${pattern}' in:\n${text}")
  endif()
endfunction()

# `text` with every regular-expression special character escaped.
function(regex_escaped out text)
  string(REGEX REPLACE "([][.+*?^$()|\\])" "\\\\\\1" escaped "${text}")
  set(${out} "${escaped}" PARENT_SCOPE)
endfunction()
