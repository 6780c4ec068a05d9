# Writes the text file IN as a C++ raw string named NAME (default kDefaultDriveJson) into OUT
# (namespace chaindrive).
if(NOT NAME)
  set(NAME kDefaultDriveJson)
endif()
file(READ ${IN} CONTENT)
get_filename_component(IN_NAME ${IN} NAME)
string(LENGTH "${CONTENT}" LEN)
file(WRITE ${OUT} "// generated from ${IN_NAME}; do not edit\n#include <string_view>\nnamespace chaindrive {\nextern const std::string_view ${NAME};\nconst std::string_view ${NAME} = R\"CHAINDRIVE_JSON(${CONTENT})CHAINDRIVE_JSON\";\n}\n")
