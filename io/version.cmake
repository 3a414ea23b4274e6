# Writes version.hpp with the source tree's git revision at build time (cmake -P, run by the
# twinflow_version target on every build; the file changes only when the revision does, so an
# unchanged tree rebuilds nothing).
execute_process(
  COMMAND git describe --always --dirty
  WORKING_DIRECTORY ${SOURCE_DIR}
  OUTPUT_VARIABLE TWINFLOW_GIT_REVISION
  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT TWINFLOW_GIT_REVISION)
  set(TWINFLOW_GIT_REVISION "unknown")
endif()
configure_file(${IN} ${OUT} @ONLY)
