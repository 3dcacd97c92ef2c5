# SPDX-License-Identifier: BSD-3-Clause
# `cmake --build build --target uninstall` (cmake -P, MANIFEST=<build>/install_manifest.txt,
# PREFIX_FILE=<build>/install_prefix.txt, the last full install's prefix): remove every file
# the last install wrote, then the folders it leaves empty: those of Aperture's own by name (a
# folder named aperture or Aperture and any below one, or the package's __pycache__ and data,
# wherever they are: a bare aperture/ folder would still import, as an empty namespace
# package), and any other at least two levels below the prefix (lib/cmake, lib/vtk/hierarchy,
# which an install into /usr/local made there), but not the prefix's own top folders (bin,
# lib, share, ...) nor the shared lib/pythonX.Y/dist-packages and share/doc, share/man.
if (NOT EXISTS "${MANIFEST}")
  message(FATAL_ERROR "no ${MANIFEST}: nothing was installed from this build tree")
endif ()
file(STRINGS "${MANIFEST}" files)
# (the prefix as the install wrote it, not guessed from the files: files of an absolute
# DOCDIR outside it made the guess /usr for /usr/local, whose bin and lib were removed)
set(known FALSE)
# (not MATCHES "^${prefix}/": a path holding regular expression characters, + or (, broke it)
function(starts_with text start result)
  string(FIND "${text}" "${start}" at)
  if (at EQUAL 0)
    set(${result} TRUE PARENT_SCOPE)
  else ()
    set(${result} FALSE PARENT_SCOPE)
  endif ()
endfunction()
# The prefix only when it is the manifest's (its package configuration in its lib folder,
# lib/cmake/Aperture, lib64/..., lib/x86_64-linux-gnu/...): a record of another install (one
# that failed before writing its manifest) would make others' folders look deep enough to
# remove
set(prefix "")
if (PREFIX_FILE AND EXISTS "${PREFIX_FILE}")
  file(READ "${PREFIX_FILE}" recorded)
  string(STRIP "${recorded}" recorded)
  string(REGEX REPLACE "/+$" "" recorded "${recorded}")
  string(LENGTH "${recorded}/" skip)
  foreach (f IN LISTS files)
    starts_with("${f}" "${recorded}/" inside)
    if (inside)
      string(SUBSTRING "${f}" ${skip} -1 relative)
      if (relative MATCHES "^lib[^/]*(/[^/]+)?/cmake/Aperture/ApertureConfig[.]cmake$")
        set(prefix "$ENV{DESTDIR}${recorded}")
        set(known TRUE)
      endif ()
    endif ()
  endforeach ()
endif ()
if (NOT known) # (a prefix of / is known, and empty: nothing is two levels below it but ours)
  message(STATUS "The install's prefix is not known for ${MANIFEST}: only Aperture's own "
    "folders left empty are removed")
endif ()
set(folders "")
foreach (f IN LISTS files)
  set(path "$ENV{DESTDIR}${f}")
  if (EXISTS "${path}" OR IS_SYMLINK "${path}")
    file(REMOVE "${path}")
  endif ()
  get_filename_component(folder "${path}" DIRECTORY)
  list(APPEND folders "${folder}")
endforeach ()
# the deepest first, each with its parents as long as they are ours by name or deep enough
# below the prefix
list(REMOVE_DUPLICATES folders)
set(candidates "")
string(LENGTH "${prefix}/" skip)
foreach (folder IN LISTS folders)
  while (NOT folder STREQUAL "/" AND NOT folder STREQUAL "")
    get_filename_component(name "${folder}" NAME)
    set(deep FALSE)
    if (prefix)
      starts_with("${folder}" "${prefix}/" inside)
      if (inside)
        string(SUBSTRING "${folder}" ${skip} -1 relative)
        if (relative MATCHES "/" AND NOT relative MATCHES
            "^(lib(64)?/python[0-9.]+(/(dist|site)-packages)?|share/(doc|man|info))$")
          set(deep TRUE)
        endif ()
      endif ()
    endif ()
    if (NOT deep AND NOT name MATCHES "^([Aa]perture|__pycache__|data|images|Documents)$"
        AND NOT folder MATCHES "/[Aa]perture/")
      break ()
    endif ()
    list(APPEND candidates "${folder}")
    get_filename_component(folder "${folder}" DIRECTORY)
  endwhile ()
endforeach ()
list(REMOVE_DUPLICATES candidates)
list(SORT candidates ORDER DESCENDING)
foreach (folder IN LISTS candidates)
  file(GLOB left "${folder}/*" "${folder}/.*")
  if (IS_DIRECTORY "${folder}" AND NOT left)
    file(REMOVE_RECURSE "${folder}") # (empty)
  endif ()
endforeach ()
list(LENGTH files count)
message(STATUS "Removed the ${count} files of ${MANIFEST}")
