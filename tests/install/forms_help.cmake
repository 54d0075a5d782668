# `shard calibrate --help` and `shard diagnose --help` show the options of every form the word
# stands for: each form's own help (`shard calibrate-effect --help`, ...) must appear in it, line
# for line, and the options that pick a form still route to it.
# Run: cmake -DSHARD=<shard> -P forms_help.cmake
set(required_vars SHARD)
include(${CMAKE_CURRENT_LIST_DIR}/command_line.cmake)

# The option lines ("  --name ...") of a help text.
function(option_lines out text)
  string(REGEX MATCHALL "\n +-[-a-zA-Z][^\n]*" lines "\n${text}")
  list(TRANSFORM lines STRIP)
  set(${out} "${lines}" PARENT_SCOPE)
endfunction()

foreach(word_forms "calibrate;calibrate;calibrate-effect;calibrate-contrast" "diagnose;diagnose;diagnose-sets")
  list(POP_FRONT word_forms word)
  run("${SHARD}" ${word} --help)
  set(combined "${run_output}")
  list(LENGTH word_forms forms)
  expect_match("shard ${word} --help" "${combined}" "^shard ${word} has ${forms} forms")
  foreach(form IN LISTS word_forms)
    run("${SHARD}" ${form} --help)
    option_lines(options "${run_output}")
    list(LENGTH options count)
    if(count LESS 3)
      message(FATAL_ERROR "shard ${form} --help shows ${count} options:\n${run_output}")
    endif()
    foreach(line IN LISTS options)
      string(FIND "${combined}" "${line}" at)
      if(at EQUAL -1)
        message(FATAL_ERROR "shard ${word} --help lacks this option of ${form}:\n${line}\n--- it shows:\n${combined}")
      endif()
    endforeach()
    message(STATUS "shard ${word} --help shows all ${count} option lines of ${form}")
  endforeach()
endforeach()

# With the options that pick a form, --help is that form's help alone.
run("${SHARD}" calibrate --with machine_compliance --help)
expect_match("calibrate --with --help" "${run_output}" "Usage: [^\n]*calibrate-effect")
run("${SHARD}" calibrate --with machine_compliance --reference A --help)
expect_match("calibrate --with --reference --help" "${run_output}" "Usage: [^\n]*calibrate-contrast")
run("${SHARD}" diagnose --reference A --help)
expect_match("diagnose --reference --help" "${run_output}" "Usage: [^\n]*diagnose-sets")
