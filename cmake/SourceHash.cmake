# Writes OUT: the constant kSourceHash, a SHA-256 over the files listed in the file LIST (a
# ;-list), the key's part for "the code" in caches of results the code computes
# (src/span/calibration_cache.h).
file(READ ${LIST} SOURCES)
set(ALL "")
foreach(f ${SOURCES})
  file(SHA256 ${f} h)
  string(APPEND ALL "${h}")
endforeach()
string(SHA256 HASH "${ALL}")
file(WRITE ${OUT}.tmp "// generated: the solver's sources, hashed; do not edit\n#include <string_view>\nnamespace chaindrive {\nextern const std::string_view kSourceHash;\nconst std::string_view kSourceHash = \"${HASH}\";\n}\n")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
