# SPDX-License-Identifier: BSD-3-Clause
# Driver of the Install-Downstream test (cmake -P): install the build into a scratch prefix,
# build the downstream project against it (the installed headers as C++11 too), run it, and
# check the installed Python package and command line.
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if (NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif ()
  message(STATUS "${what}: ok\n${out}")
endfunction()

run("install" "${CMAKE_COMMAND}" --install "${APERTURE_BUILD_DIR}" --prefix "${prefix}")
run("configure downstream" "${CMAKE_COMMAND}" -S "${APERTURE_SOURCE_DIR}/Testing/Downstream/project"
  -B "${WORK_DIR}/build" "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_BUILD_TYPE=Release)
run("build downstream" "${CMAKE_COMMAND}" --build "${WORK_DIR}/build")
run("run downstream" "${WORK_DIR}/build/downstream")

# The installed libraries and modules look for libraries inside the prefix only (the
# libraries' $ORIGIN/../../.. had them load VTK and GDAL from two folders above the prefix,
# under /tmp here, before the system's, until 2026-12-07)
file(GLOB_RECURSE elves "${prefix}/*.so" "${prefix}/*.so.*")
foreach (elf IN LISTS elves)
  file(READ_ELF "${elf}" RUNPATH runpath)
  get_filename_component(origin "${elf}" DIRECTORY)
  string(REPLACE ":" ";" runpath "${runpath}")
  foreach (entry IN LISTS runpath)
    string(REPLACE "$ORIGIN" "${origin}" where "${entry}")
    get_filename_component(where "${where}" ABSOLUTE)
    string(FIND "${where}/" "${prefix}/" at)
    if (NOT at EQUAL 0)
      message(FATAL_ERROR "${elf} looks for libraries in ${where} (RUNPATH ${entry}), outside "
        "the prefix ${prefix}")
    endif ()
  endforeach ()
endforeach ()

# The modules keep the C core's functions to themselves (none exported: each links its copy)
find_program(NM nm)
if (NM)
  file(GLOB modules "${prefix}/lib/libAperture*.so")
  foreach (module IN LISTS modules)
    execute_process(COMMAND "${NM}" -D --defined-only "${module}" OUTPUT_VARIABLE symbols)
    if (symbols MATCHES " ap_[a-z0-9_]+")
      message(FATAL_ERROR "${module} exports the C core's ${CMAKE_MATCH_0}")
    endif ()
  endforeach ()
endif ()

# A component it does not have is named (check_required_components said only that Aperture
# was not found, until 2026-12-07)
file(WRITE "${WORK_DIR}/misspelt/CMakeLists.txt"
  "cmake_minimum_required(VERSION 3.16)\nproject(misspelt C CXX)\n"
  "find_package(Aperture REQUIRED COMPONENTS Filter IO)\n")
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${WORK_DIR}/misspelt" -B "${WORK_DIR}/misspelt/b"
  "-DCMAKE_PREFIX_PATH=${prefix}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if (rc EQUAL 0 OR NOT err MATCHES "Aperture has no component Filter;[ \n]+its[ \n]+components")
  message(FATAL_ERROR "find_package(Aperture COMPONENTS Filter) (${rc}):\n${err}")
endif ()

if (WRAP_PYTHON)
  # The installed package imports with only PYTHONPATH pointing at the prefix (nothing from the
  # build tree), and the installed launcher needs no environment at all.
  string(CONCAT import_check
    "import aperture\n"
    "p = aperture.__file__\n"
    "assert p.startswith('${prefix}'), p\n"
    "r = aperture.vtkApertureDEMReader()\n"
    "r.SetFileName(aperture.default_dem())\n"
    "r.Update()\n"
    "assert r.GetOutput().GetNumberOfPoints() == 403 * 344\n"
    "print('import ok', p)\n")
  run("import from the install prefix" "${CMAKE_COMMAND}" -E env
    "PYTHONPATH=${prefix}/${PYTHON_DESTINATION}" "${PYTHON}" -c "${import_check}")
  run("installed command line" "${prefix}/bin/aperture" info --json)
  # an install over one of before 2026-12-06 takes away its module default_dem.py, which
  # shadowed the function aperture.default_dem()
  set(old_module "${prefix}/${PYTHON_DESTINATION}/aperture/default_dem.py")
  file(WRITE "${old_module}" "raise SystemExit('the old module')\n")
  run("install again" "${CMAKE_COMMAND}" --install "${APERTURE_BUILD_DIR}" --prefix "${prefix}")
  if (EXISTS "${old_module}")
    message(FATAL_ERROR "the install left ${old_module}")
  endif ()
  # byte-compiled by the install (checked without importing, which could write it itself)
  string(CONCAT compiled_check
    "import importlib.util, os\n"
    "p = importlib.util.cache_from_source('${prefix}/${PYTHON_DESTINATION}/aperture/cli.py')\n"
    "assert os.path.exists(p), p\n"
    "print(p)\n")
  run("byte-compiled at install" "${PYTHON}" -c "${compiled_check}")
endif ()

# the licence and the documentation, the README's pictures beside it, and every file its links
# name (bench/results-bake.md, ...: read from the README, so that a new link is checked too)
file(READ "${APERTURE_SOURCE_DIR}/README.md" readme)
# (a link's "](" marked first: a list element holding a square bracket keeps the semicolons
# after it, so the matches must hold none)
string(REPLACE "](" " @LINK@" readme "${readme}")
string(REGEX MATCHALL "@LINK@[^)#; ]+" linked "${readme}")
list(TRANSFORM linked REPLACE "^@LINK@" "")
list(FILTER linked EXCLUDE REGEX "^[A-Za-z][A-Za-z0-9+.-]*:") # (URLs)
list(REMOVE_DUPLICATES linked)
foreach (doc LICENSE README.md ${linked})
  if (NOT EXISTS "${prefix}/share/doc/Aperture/${doc}")
    message(FATAL_ERROR "the install has no share/doc/Aperture/${doc}")
  endif ()
endforeach ()

# install_manifest.txt names every file the install made (the byte-compiled ones too: an
# uninstall by it left them until 2026-12-07, and `import aperture` then found an empty
# namespace package), and the uninstall target removes them and the folders of ours left
# empty, so that the package no longer imports.
set(manifest_path "${APERTURE_BUILD_DIR}/install_manifest.txt")
file(STRINGS "${manifest_path}" manifest)
file(GLOB_RECURSE installed LIST_DIRECTORIES false "${prefix}/*")
list(SORT manifest)
list(SORT installed)
if (NOT manifest STREQUAL installed)
  set(unlisted ${installed})
  list(REMOVE_ITEM unlisted ${manifest})
  message(FATAL_ERROR "install_manifest.txt does not name what was installed; unnamed: "
    "${unlisted}")
endif ()
# Utilities/Uninstall.cmake on a manifest and a prefix record, in the environment ARGN
function(uninstall what manifest prefix_record)
  run("${what}" "${CMAKE_COMMAND}" -E env ${ARGN} "${CMAKE_COMMAND}"
    "-DMANIFEST=${manifest}" "-DPREFIX_FILE=${prefix_record}"
    -P "${APERTURE_SOURCE_DIR}/Utilities/Uninstall.cmake")
endfunction()
set(prefix_record "${APERTURE_BUILD_DIR}/install_prefix.txt")
# (no file, and no folder but the prefix's own top ones, bin, lib, share, and the shared
# lib/pythonX.Y/dist-packages and share/doc: lib/cmake and lib/vtk/hierarchy were left empty
# until 2026-12-07)
function(check_nothing_left root install_prefix)
  file(GLOB_RECURSE left LIST_DIRECTORIES true "${root}/*")
  string(LENGTH "${install_prefix}/" skip)
  foreach (path IN LISTS left)
    string(FIND "${path}/" "${install_prefix}/" at)
    set(relative "")
    if (at EQUAL 0) # (else a folder on the stage's way to the prefix)
      string(SUBSTRING "${path}/" ${skip} -1 relative)
      string(REGEX REPLACE "/$" "" relative "${relative}")
    endif ()
    if (NOT IS_DIRECTORY "${path}" OR path MATCHES "/[Aa]perture(/|$)" OR
        (relative MATCHES "/" AND NOT relative MATCHES
          "^(lib(64)?/python[0-9.]+(/(dist|site)-packages)?|share/doc)$"))
      message(FATAL_ERROR "the uninstall left ${path}")
    endif ()
  endforeach ()
endfunction()
uninstall("uninstall" "${manifest_path}" "${prefix_record}")
check_nothing_left("${prefix}" "${prefix}")
if (WRAP_PYTHON)
  run("no package after the uninstall" "${CMAKE_COMMAND}" -E env
    "PYTHONPATH=${prefix}/${PYTHON_DESTINATION}" "${PYTHON}" -c
    "import importlib.util as u; assert u.find_spec('aperture') is None, u.find_spec('aperture')")
endif ()
# Staged (DESTDIR): the manifest names the files where they will be, without the stage, and
# the uninstall with the same DESTDIR removes them.
set(stage "${WORK_DIR}/stage")
run("staged install" "${CMAKE_COMMAND}" -E env "DESTDIR=${stage}" "${CMAKE_COMMAND}" --install
  "${APERTURE_BUILD_DIR}" --prefix "${WORK_DIR}/usr")
file(STRINGS "${manifest_path}" manifest)
foreach (f IN LISTS manifest)
  if (f MATCHES "^${stage}/" OR NOT EXISTS "${stage}${f}")
    message(FATAL_ERROR "the staged install's manifest names ${f}")
  endif ()
  # (its byte code names the files where they will be: the stage's path was in every .pyc
  # until 2026-12-07)
  if (f MATCHES "[.]pyc$")
    file(STRINGS "${stage}${f}" staged REGEX "${stage}")
    if (staged)
      message(FATAL_ERROR "${stage}${f} names the stage: ${staged}")
    endif ()
  endif ()
endforeach ()
uninstall("uninstall" "${manifest_path}" "${prefix_record}" "DESTDIR=${stage}")
check_nothing_left("${stage}" "${stage}${WORK_DIR}/usr")
list(LENGTH manifest count)
message(STATUS "install_manifest.txt names all ${count} files installed; uninstalled: ok")

# The uninstall keeps the prefix's own folders, which Debian's /usr/local has empty, when a
# file lies outside it (an absolute DOCDIR: the prefix guessed from the files was then /usr,
# and /usr/local/bin, include and lib were removed, until 2026-12-07), and removes the
# package's folders outside it too.
set(fake "${WORK_DIR}/fake")
foreach (d usr/local/bin usr/local/include usr/local/lib/python3.11/dist-packages
    usr/share/doc/other)
  file(MAKE_DIRECTORY "${fake}/${d}")
endforeach ()
set(fake_files /usr/local/lib/cmake/Aperture/ApertureConfig.cmake
  /usr/local/lib/python3.11/dist-packages/aperture/__pycache__/cli.pyc
  /usr/local/lib/vtk/hierarchy/Aperture/Filters.txt /usr/share/doc/Aperture/README.md
  /usr/share/doc/Aperture/bench/results-bake.md)
string(REPLACE ";" "\n" fake_manifest "${fake_files}")
file(WRITE "${WORK_DIR}/fake-manifest.txt" "${fake_manifest}\n")
file(WRITE "${WORK_DIR}/fake-prefix.txt" "/usr/local")
foreach (f IN LISTS fake_files)
  file(WRITE "${fake}${f}" "")
endforeach ()
uninstall("uninstall of a prefix with a folder outside it" "${WORK_DIR}/fake-manifest.txt"
  "${WORK_DIR}/fake-prefix.txt" "DESTDIR=${fake}")
file(GLOB_RECURSE left LIST_DIRECTORIES true RELATIVE "${fake}" "${fake}/*")
list(SORT left)
set(kept usr usr/local usr/local/bin usr/local/include usr/local/lib usr/local/lib/python3.11
  usr/local/lib/python3.11/dist-packages usr/share usr/share/doc usr/share/doc/other)
if (NOT left STREQUAL kept)
  message(FATAL_ERROR "the uninstall left ${left}, not ${kept}")
endif ()
# A record of another prefix (an install that failed before writing its manifest) is not
# taken: only the folders ours by name go, and /usr/local's own stay (as /usr, the record
# made bin, include and lib two levels deep, and removed them)
foreach (f IN LISTS fake_files)
  file(WRITE "${fake}${f}" "")
endforeach ()
file(WRITE "${WORK_DIR}/fake-prefix.txt" "/usr")
uninstall("uninstall with another install's prefix recorded" "${WORK_DIR}/fake-manifest.txt"
  "${WORK_DIR}/fake-prefix.txt" "DESTDIR=${fake}")
file(GLOB_RECURSE left LIST_DIRECTORIES true RELATIVE "${fake}" "${fake}/*")
foreach (d IN LISTS kept)
  list(FIND left "${d}" at)
  if (at EQUAL -1)
    message(FATAL_ERROR "the uninstall removed ${d}")
  endif ()
endforeach ()
if (left MATCHES "[Aa]perture")
  message(FATAL_ERROR "the uninstall left ${left}")
endif ()
