# Eigen 3.4 and nlohmann-json (header only), SUNDIALS 6.4 and SuiteSparse KLU (static archives,
# so that the FMU binaries are self-contained).
#
# Native build: all from Debian 12 packages. Cross builds of the shipped FMUs (cmake/toolchains,
# python -m harness package): from CHAINDRIVE_DEPS_PREFIX, a prefix with include/ (eigen3/,
# nlohmann/, suitesparse/, the SUNDIALS folders) and lib/ (the archives) for the target; nothing
# of the build machine's /usr/include enters a cross build.
set(CHAINDRIVE_DEPS_PREFIX "" CACHE PATH "headers and static archives of the dependencies for a cross build")

set(_static_names
  sundials_cvode sundials_arkode sundials_sunlinsolklu sundials_sunlinsolband sundials_sunlinsoldense
  sundials_sunmatrixsparse sundials_sunmatrixband sundials_sunmatrixdense
  sundials_sunnonlinsolnewton sundials_sunnonlinsolfixedpoint sundials_nvecserial sundials_generic
  klu amd colamd btf suitesparseconfig)

add_library(chaindrive_deps INTERFACE)
if(CHAINDRIVE_DEPS_PREFIX)
  set(_deps_include ${CHAINDRIVE_DEPS_PREFIX}/include)
  target_include_directories(chaindrive_deps SYSTEM INTERFACE ${_deps_include} ${_deps_include}/eigen3
                             ${_deps_include}/suitesparse)
  set(_find_archive PATHS ${CHAINDRIVE_DEPS_PREFIX}/lib NO_DEFAULT_PATH NO_CMAKE_FIND_ROOT_PATH)
else()
  find_package(Eigen3 3.4 REQUIRED NO_MODULE)
  find_package(nlohmann_json 3.10 REQUIRED)
  find_package(SUNDIALS 6.4 REQUIRED)
  if(SUNDIALS_VERSION VERSION_GREATER_EQUAL 7.0)
    message(FATAL_ERROR "SUNDIALS ${SUNDIALS_VERSION} found; this code uses the 6.x API")
  endif()
  target_include_directories(chaindrive_deps SYSTEM INTERFACE /usr/include/suitesparse)
  get_target_property(_eigen_inc Eigen3::Eigen INTERFACE_INCLUDE_DIRECTORIES)
  target_include_directories(chaindrive_deps SYSTEM INTERFACE ${_eigen_inc})
  get_target_property(_json_inc nlohmann_json::nlohmann_json INTERFACE_INCLUDE_DIRECTORIES)
  target_include_directories(chaindrive_deps SYSTEM INTERFACE ${_json_inc})
  set(_find_archive "")
endif()

# The archives as linked: copies whose references to the C runtime's transcendental functions
# are renamed to the project's own (cmake/Determinism.cmake), so that SUNDIALS' step-size control
# computes the same bits on every platform.
set(_static_libs "")
foreach(name IN LISTS _static_names)
  find_library(LIB_${name} NAMES lib${name}.a ${_find_archive} REQUIRED)
  chaindrive_redirect_crt_math(${LIB_${name}} _redirected)
  list(APPEND _static_libs ${_redirected})
endforeach()
add_custom_target(chaindrive_redirected_archives DEPENDS ${_static_libs})
add_dependencies(chaindrive_deps chaindrive_redirected_archives)

# link group: the archives reference each other
if(WIN32)
  target_link_libraries(chaindrive_deps INTERFACE -Wl,--start-group ${_static_libs} -Wl,--end-group)
else()
  target_link_libraries(chaindrive_deps INTERFACE -Wl,--start-group ${_static_libs} -Wl,--end-group m)
endif()
