# Debian's paraview-dev 5.11 lists files in its CMake package that are not installed with it:
# Python extension modules under names it does not install (VTKPython, ParaViewPython targets),
# and /usr/bin/pvpython, which comes with python3-paraview, a package that conflicts with
# Debian's own VTK (python3-vtk9, needed by the rest of this project). CMake's import check then
# stops every find_package(ParaView). The plugin uses none of those files: each affected
# targets file is loaded here without its existence check (same targets, same locations), so
# that ParaView's own find_package sees its targets already defined and skips the file.
function(mfadvr_import_without_check targets_file)
  if(NOT EXISTS "${targets_file}")
    return()
  endif()
  get_filename_component(dir "${targets_file}" DIRECTORY)
  get_filename_component(stem "${targets_file}" NAME_WE)
  file(GLOB config_files "${dir}/${stem}-*.cmake")
  set(missing "")
  foreach(config_file IN LISTS config_files)
    file(STRINGS "${config_file}" lines REGEX "_cmake_import_check_files_for_")
    foreach(line IN LISTS lines)
      string(REGEX MATCHALL "\"[^\"]+\"" paths "${line}")
      foreach(path IN LISTS paths)
        string(REPLACE "\"" "" path "${path}")
        string(REPLACE "\${_IMPORT_PREFIX}" "/usr" path "${path}")
        if(NOT EXISTS "${path}" AND missing STREQUAL "")
          set(missing "${path}")
        endif()
      endforeach()
    endforeach()
  endforeach()
  if(missing STREQUAL "")
    return()
  endif()
  file(READ "${targets_file}" text)
  string(REPLACE "\${CMAKE_CURRENT_LIST_FILE}" "${targets_file}" text "${text}")
  string(REPLACE "\${CMAKE_CURRENT_LIST_DIR}" "${dir}" text "${text}")
  string(REPLACE "if(NOT EXISTS \"\${_cmake_file}\")" "if(FALSE)" text "${text}")
  set(copy "${CMAKE_BINARY_DIR}/paraview-package/${stem}-unchecked.cmake")
  file(WRITE "${copy}" "${text}")
  include("${copy}")
  message(STATUS "mfadvr: ${stem} names files that are not installed (${missing}); loaded "
                 "without the existence check (the plugin does not use them)")
endfunction()

foreach(targets IN ITEMS "vtk/VTKPython-targets" "ParaViewPython-targets" "ParaViewTools-targets")
  mfadvr_import_without_check("/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11/${targets}.cmake")
endforeach()

# The wrapping hierarchy files of ParaView's VTK modules also ship in python3-paraview. When
# they are not installed, `scripts/install-deps.sh --paraview` unpacks that package (without
# installing it) under MFADVR_PARAVIEW_PYTHON_ROOT, and the modules' hierarchy properties are
# pointed there. Call after find_package(ParaView).
set(MFADVR_PARAVIEW_PYTHON_ROOT "${CMAKE_SOURCE_DIR}/build/deps/python3-paraview"
    CACHE PATH "python3-paraview unpacked (its Python modules, pvpython, wrapping hierarchies)")
function(mfadvr_redirect_paraview_hierarchies)
  get_property(targets DIRECTORY "${CMAKE_SOURCE_DIR}" PROPERTY IMPORTED_TARGETS)
  set(redirected 0)
  foreach(target IN LISTS targets)
    get_property(file TARGET "${target}" PROPERTY INTERFACE_vtk_module_hierarchy)
    if(file AND NOT EXISTS "${file}")
      string(REGEX REPLACE "^.*/lib/x86_64-linux-gnu/vtk/hierarchy/"
                           "${MFADVR_PARAVIEW_PYTHON_ROOT}/usr/lib/x86_64-linux-gnu/vtk/hierarchy/"
                           moved "${file}")
      if(NOT EXISTS "${moved}")
        message(FATAL_ERROR "ParaView's wrapping hierarchy ${file} is missing (Debian ships it in "
                            "python3-paraview). Run scripts/install-deps.sh --paraview, which "
                            "unpacks that package under ${MFADVR_PARAVIEW_PYTHON_ROOT}.")
      endif()
      set_property(TARGET "${target}" PROPERTY INTERFACE_vtk_module_hierarchy "${moved}")
      math(EXPR redirected "${redirected} + 1")
    endif()
  endforeach()
  if(redirected GREATER 0)
    message(STATUS "mfadvr: ${redirected} ParaView module hierarchies read from "
                   "${MFADVR_PARAVIEW_PYTHON_ROOT}")
  endif()
endfunction()
