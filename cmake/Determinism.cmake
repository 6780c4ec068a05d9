# The same bits on every platform, compiler and C runtime (the chaotic link dynamics turn one
# different rounding into a visibly different run):
#
# - no fused multiply-add contracted from a * b + c, whatever the target; the AVX2 loops of
#   src/dynamics/link_loops.cpp are compiled without FMA and give the SSE2 loops' bits;
# - every transcendental function is the project's own (src/math/): C runtimes compute them
#   differently (against glibc, a Windows runtime's cbrt differs on 47 % of inputs, atan2 on 18 %,
#   exp on 10 %), and glibc itself picks FMA or non-FMA code at run time. The static archives of
#   the dependencies have their references renamed to ours (chaindrive_redirect_crt_math), and
#   the programs and FMUs are linked with every such function wrapped to a symbol that does not
#   exist (CHAINDRIVE_CRT_MATH_GUARD), so that any reference left fails the link, naming its
#   caller (GNU ld and zig's ELF linker; zig's Windows linker ignores --wrap, so the package
#   checks the Windows binaries' link inputs with nm instead: harness/package/inspect.py).
#   Exact functions (sqrt, fabs, floor, nearbyint, lround, fmod, nextafter, ...) give
#   the same bits everywhere and stay the C runtime's.
add_compile_options(-ffp-contract=off)
# (nothing here reads errno: a square root is then one instruction, not a test and a call)
add_compile_options(-fno-math-errno)

set(CHAINDRIVE_CRT_TRANSCENDENTALS
  sin cos tan sincos asin acos atan atan2 sinh cosh tanh asinh acosh atanh
  exp exp2 exp10 expm1 log log2 log10 log1p pow cbrt hypot erf erfc lgamma tgamma)
option(CHAINDRIVE_LINK_GUARD "fail the link of the programs and FMUs on any C runtime transcendental" ON)
set(CHAINDRIVE_CRT_MATH_GUARD "")
foreach(fn IN LISTS CHAINDRIVE_CRT_TRANSCENDENTALS)
  if(NOT CHAINDRIVE_LINK_GUARD)
    break()
  endif()
  foreach(variant ${fn} ${fn}f ${fn}l)
    list(APPEND CHAINDRIVE_CRT_MATH_GUARD "-Wl,--wrap=${variant}")
  endforeach()
endforeach()

# The C runtime functions that our own replace in third-party archives: name, then ours.
set(CHAINDRIVE_CRT_MATH_RENAMES "pow chaindrive_pow")
find_program(CHAINDRIVE_OBJCOPY NAMES objcopy REQUIRED)  # (GNU's: ELF and PE/COFF alike)
file(CONFIGURE OUTPUT ${CMAKE_BINARY_DIR}/crt_math_renames.txt CONTENT "${CHAINDRIVE_CRT_MATH_RENAMES}\n")

# A copy of the static archive `archive` in the build tree with its references renamed; its path
# into `out`.
function(chaindrive_redirect_crt_math archive out)
  get_filename_component(name ${archive} NAME)
  set(copy ${CMAKE_BINARY_DIR}/redirected-archives/${name})
  add_custom_command(
    OUTPUT ${copy}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_BINARY_DIR}/redirected-archives
    COMMAND ${CHAINDRIVE_OBJCOPY} --redefine-syms=${CMAKE_BINARY_DIR}/crt_math_renames.txt ${archive} ${copy}
    DEPENDS ${archive} ${CMAKE_BINARY_DIR}/crt_math_renames.txt
    COMMENT "Renaming the C runtime's transcendental functions in ${name}")
  set(${out} ${copy} PARENT_SCOPE)
endfunction()
