# Writes the text file IN as a C++ raw string into OUT (namespace chaindrive).
file(READ ${IN} CONTENT)
string(LENGTH "${CONTENT}" LEN)
file(WRITE ${OUT} "// generated from ${IN}; do not edit\n#include <string_view>\nnamespace chaindrive {\nextern const std::string_view kDefaultDriveJson;\nconst std::string_view kDefaultDriveJson = R\"CHAINDRIVE_JSON(${CONTENT})CHAINDRIVE_JSON\";\n}\n")
