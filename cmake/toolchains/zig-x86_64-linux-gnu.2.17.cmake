# linux64 for every glibc from 2.17 (manylinux2014's floor: RHEL 7 and later, Ubuntu 14.04 and later)
set(ZIG_TARGET x86_64-linux-gnu.2.17)
include(${CMAKE_CURRENT_LIST_DIR}/zig.cmake)
