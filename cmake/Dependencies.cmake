# Eigen 3.4, SUNDIALS 6.4 (static archives, so the FMU binary is self-contained),
# SuiteSparse KLU (static), nlohmann-json (header only). All from Debian 12 packages.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(SUNDIALS 6.4 REQUIRED)
if(SUNDIALS_VERSION VERSION_GREATER_EQUAL 7.0)
  message(FATAL_ERROR "SUNDIALS ${SUNDIALS_VERSION} found; this code uses the 6.x API")
endif()

set(_static_names
  sundials_cvode sundials_arkode sundials_sunlinsolklu sundials_sunlinsolband sundials_sunlinsoldense
  sundials_sunmatrixsparse sundials_sunmatrixband sundials_sunmatrixdense
  sundials_sunnonlinsolnewton sundials_sunnonlinsolfixedpoint sundials_nvecserial sundials_generic
  klu amd colamd btf suitesparseconfig)
set(_static_libs "")
foreach(name IN LISTS _static_names)
  find_library(LIB_${name} NAMES lib${name}.a REQUIRED)
  list(APPEND _static_libs ${LIB_${name}})
endforeach()

add_library(chaindrive_deps INTERFACE)
target_include_directories(chaindrive_deps SYSTEM INTERFACE /usr/include/suitesparse)
get_target_property(_eigen_inc Eigen3::Eigen INTERFACE_INCLUDE_DIRECTORIES)
target_include_directories(chaindrive_deps SYSTEM INTERFACE ${_eigen_inc})
get_target_property(_json_inc nlohmann_json::nlohmann_json INTERFACE_INCLUDE_DIRECTORIES)
target_include_directories(chaindrive_deps SYSTEM INTERFACE ${_json_inc})
# link group: the archives reference each other
target_link_libraries(chaindrive_deps INTERFACE -Wl,--start-group ${_static_libs} -Wl,--end-group m)
