// A file name as FMI and the drive descriptions carry it (UTF-8) as a path of the operating
// system. On Windows the narrow file functions read names in the ANSI code page, so a resources
// folder under C:\Users\Jürgen\AppData\Local\Temp would not open; std::filesystem::path opens
// it with the wide ones. Elsewhere the name is the path as it is.
#pragma once

#include <filesystem>
#include <string>

namespace chaindrive {

inline std::filesystem::path utf8Path(const std::string& name) { return std::filesystem::u8path(name); }

}  // namespace chaindrive
