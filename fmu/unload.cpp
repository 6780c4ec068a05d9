// An importer that unloads the FMU (dlclose, as fmpy does at fmi2FreeInstance's end) before its
// process exits: the FMU's exit handlers (the destructors of function-local statics, registered
// with __cxa_atexit under this library's handle) must run and leave the process's exit list at
// the unload. The C runtime's start files of a shared library do that (crtbeginS); a library
// linked without them (zig's linux targets: the packaged linux64 binary) left them in the list,
// and the importing process crashed at its exit, after the FMU was gone. So the library does it
// itself; where the start files have done it already, nothing is left to run.
#if defined(__linux__)
extern "C" void __cxa_finalize(void* dso);
extern void* __dso_handle;  // (as the compiler declares it: a unity build sees both)

namespace {
__attribute__((destructor)) void runExitHandlersAtUnload() { __cxa_finalize(&__dso_handle); }
}  // namespace
#endif
