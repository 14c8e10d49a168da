# Writes VERSION_FILE (a C header: VIQU_VERSION, VIQU_GIT_COMMIT) from VERSION and the git commit
# of SOURCE_DIR, only when its content changes. Run as `cmake -P` at every build (apps/).
execute_process(COMMAND git -C "${SOURCE_DIR}" describe --always --dirty --abbrev=12
                OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR commit STREQUAL "")
  set(commit "unknown: not built from a git checkout")
endif()
set(content "#pragma once\n#define VIQU_VERSION \"${VERSION}\"\n#define VIQU_GIT_COMMIT \"${commit}\"\n")
set(old "")
if(EXISTS "${VERSION_FILE}")
  file(READ "${VERSION_FILE}" old)
endif()
if(NOT old STREQUAL content)
  file(WRITE "${VERSION_FILE}" "${content}")
endif()
