# m4d.pc's prefix, libdir and includedir, none fixed at configure time: the prefix is found from
# the .pc file's own folder (${pcfiledir}, which pkg-config and pkgconf both set), so that
# `cmake --install build --prefix X` and a moved installation give right flags. A libdir or
# includedir given as an absolute path (as Debian's packaging does) is kept as given.
function(m4d_pkg_config_paths pc_dir)
  if(IS_ABSOLUTE "${pc_dir}")
    set(M4D_PC_PREFIX "${CMAKE_INSTALL_PREFIX}" PARENT_SCOPE)
  else()
    # One ".." per folder between the prefix and the .pc file's folder.
    string(REGEX REPLACE "[^/]+" ".." up "${pc_dir}")
    set(M4D_PC_PREFIX "\${pcfiledir}/${up}" PARENT_SCOPE)
  endif()
  foreach(kind LIBDIR INCLUDEDIR)
    if(IS_ABSOLUTE "${CMAKE_INSTALL_${kind}}")
      set(M4D_PC_${kind} "${CMAKE_INSTALL_${kind}}" PARENT_SCOPE)
    else()
      set(M4D_PC_${kind} "\${prefix}/${CMAKE_INSTALL_${kind}}" PARENT_SCOPE)
    endif()
  endforeach()
endfunction()
