# Cross-compiling with zig's Clang (PyPI's ziglang): the shipped FMU binaries. One compiler for
# every platform: an old glibc as the floor on Linux (its symbol versions are chosen by the
# target, x86_64-linux-gnu.2.17), the MinGW-w64 C runtime on Windows, and LLVM's libc++ linked
# in statically on both. Set ZIG_TARGET before including this file; ZIG_PYTHON is a Python with
# the ziglang package (default: python3 on the PATH).
if(NOT ZIG_TARGET)
  message(FATAL_ERROR "zig.cmake: set ZIG_TARGET (e.g. x86_64-windows-gnu) first")
endif()
if(ZIG_TARGET MATCHES "windows")
  set(CMAKE_SYSTEM_NAME Windows)
else()
  set(CMAKE_SYSTEM_NAME Linux)
endif()
set(CMAKE_SYSTEM_PROCESSOR x86_64)

# zig's executable from ZIG_PYTHON's ziglang package, kept in the environment for the
# try_compile projects of a dependency's build (they read this file again, in this process)
if(NOT DEFINED ENV{CHAINDRIVE_ZIG})
  if(NOT ZIG_PYTHON)
    set(ZIG_PYTHON "$ENV{ZIG_PYTHON}")
  endif()
  if(NOT ZIG_PYTHON)
    set(ZIG_PYTHON python3)
  endif()
  execute_process(COMMAND ${ZIG_PYTHON} -c "import ziglang, os; print(os.path.join(os.path.dirname(ziglang.__file__), 'zig'))"
                  OUTPUT_VARIABLE _zig OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE _zig_found)
  if(NOT _zig_found EQUAL 0 OR NOT EXISTS "${_zig}")
    message(FATAL_ERROR "zig.cmake: no ziglang package in ${ZIG_PYTHON} (pip install ziglang)")
  endif()
  set(ENV{CHAINDRIVE_ZIG} "${_zig}")
endif()
set(ZIG_EXECUTABLE "$ENV{CHAINDRIVE_ZIG}")

# CMake wants one program per tool: small scripts that call zig's with the target.
# zig builds the target's C runtime and libc++ from source the first time a link needs them (on
# two cores some 15 minutes for Windows, one source at a time), once per optimisation mode, debug
# information and position-independence: CMake's compiler checks link with no -O and no -s (zig's
# Debug mode, a runtime with debug information), the FMUs with -O3 and -s (CMakeLists.txt), so a
# fresh zig cache built every runtime twice (a cold win64 build: 2072 s on 2 cores, 1003 s with
# this). With -O2 -s (and -fPIC on Linux) in front of CMake's flags the checks link against the
# runtime the FMUs' link uses. The FMUs' code is unchanged: zig compiles -O2 and -O3 alike (its
# ReleaseFast), CMake gives them -fPIC already, and -s only leaves out the debug information the
# link stripped before (the win64 DLL's .text bit-identical; only its exception tables' call-site
# ranges, laid out without debug locations, differ).
set(_zig_runtime_flags "-O2 -s")
if(NOT ZIG_TARGET MATCHES "windows")
  string(APPEND _zig_runtime_flags " -fPIC")
endif()
set(_zig_tools ${CMAKE_BINARY_DIR}/zig-tools)
foreach(tool cc c++ ar ranlib)
  set(_args "${tool}")
  if(tool STREQUAL "cc" OR tool STREQUAL "c++")
    set(_args "${tool} -target ${ZIG_TARGET} ${_zig_runtime_flags}")
  endif()
  file(WRITE ${_zig_tools}/${tool} "#!/bin/sh\nexec \"${ZIG_EXECUTABLE}\" ${_args} \"$@\"\n")
  file(CHMOD ${_zig_tools}/${tool} PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
       WORLD_READ WORLD_EXECUTE)
endforeach()
set(CMAKE_C_COMPILER ${_zig_tools}/cc)
set(CMAKE_CXX_COMPILER ${_zig_tools}/c++)
set(CMAKE_AR ${_zig_tools}/ar CACHE FILEPATH "zig ar")
set(CMAKE_RANLIB ${_zig_tools}/ranlib CACHE FILEPATH "zig ranlib")

# nothing from the build machine's /usr/include or /usr/lib: dependencies are named explicitly
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
