# The CMake link graph, for the layering check (scripts/check_layering.py
# --targets, CTest layering.targets): hsmap_write_target_links(<file>) writes
# one line per target of the project, "name<TAB>folder of its
# CMakeLists.txt<TAB>its links (;-separated)". Call it once every target is
# defined, e.g. deferred to the end of the top-level directory.
include_guard(GLOBAL)

function(hsmap_write_target_links file)
  set(table "")
  set(folders "${PROJECT_SOURCE_DIR}")
  while(folders)
    list(POP_FRONT folders folder)
    get_property(subfolders DIRECTORY "${folder}" PROPERTY SUBDIRECTORIES)
    list(APPEND folders ${subfolders})
    get_property(targets DIRECTORY "${folder}" PROPERTY BUILDSYSTEM_TARGETS)
    foreach(target IN LISTS targets)
      set(links "")
      foreach(property LINK_LIBRARIES INTERFACE_LINK_LIBRARIES)
        get_target_property(value ${target} ${property})
        if(value)
          list(APPEND links ${value})
        endif()
      endforeach()
      string(APPEND table "${target}\t${folder}\t${links}\n")
    endforeach()
  endwhile()
  file(WRITE "${file}" "${table}")
endfunction()
