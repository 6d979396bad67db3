# Runs one scene for a few steps and checks the outcome (used by tests/scenes/CMakeLists.txt):
#   cmake -DFASCIA_RUN=<fascia-run> -DSCENE=<scene.xml> -DOUTPUT=<folder> -DSTEPS=<n> -P RunScene.cmake
# Passes when fascia-run exits with code 0 and prints its summary line "fascia-run: <n> steps, ...".
# The output folder is emptied first, so every run starts clean.
foreach(var FASCIA_RUN SCENE OUTPUT STEPS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "RunScene.cmake: -D${var}=... is required")
  endif()
endforeach()

file(REMOVE_RECURSE "${OUTPUT}")
file(MAKE_DIRECTORY "${OUTPUT}")
execute_process(
  COMMAND "${FASCIA_RUN}" "${SCENE}" --steps ${STEPS} --quiet --output "${OUTPUT}"
  RESULT_VARIABLE rc
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err)

if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "${SCENE}: fascia-run exited with '${rc}' (0 expected)\n"
                      "stdout:\n${out}\nstderr:\n${err}")
endif()
if(NOT out MATCHES "fascia-run: ${STEPS} steps, ")
  message(FATAL_ERROR "${SCENE}: no summary line 'fascia-run: ${STEPS} steps, ...' on stdout\n"
                      "stdout:\n${out}\nstderr:\n${err}")
endif()
message(STATUS "${out}")
