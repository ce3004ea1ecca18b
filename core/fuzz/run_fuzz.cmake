# CTest's bounded fuzz run: a fresh corpus folder every time (libFuzzer adds the inputs it keeps
# to its first folder; starting from the seeds alone keeps the run the same run after run), then
# EXE -runs=RUNS -seed=1 on it and SEEDS. Fails with libFuzzer's exit code.
#   cmake -DEXE=... -DCORPUS=... -DSEEDS=... -DRUNS=... -DARTIFACTS=... -P run_fuzz.cmake
file(REMOVE_RECURSE ${CORPUS})
file(MAKE_DIRECTORY ${CORPUS} ${ARTIFACTS})
execute_process(
  COMMAND ${EXE} -runs=${RUNS} -seed=1 -max_len=4096 -artifact_prefix=${ARTIFACTS}/ ${CORPUS} ${SEEDS}
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${EXE}: libFuzzer exit ${rc} (the input is in ${ARTIFACTS})")
endif()
