// SPDX-License-Identifier: BSD-3-Clause
// Private to Aperture::IO: what the writers (vtkApertureDEMWriter, vtkApertureEXRWriter) may
// create or replace at their FileName, and what the readers may not open (a named pipe).
#ifndef vtkApertureOutputFile_h
#define vtkApertureOutputFile_h

#include <sys/stat.h>

#include <string>

/** What `st` is when it is not a regular file: "a folder", "a device", "a pipe", "a socket",
 *  else "not a regular file". */
inline const char* vtkApertureFileKind(const struct stat& st)
{
  return S_ISDIR(st.st_mode) ? "a folder"
    : (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) ? "a device"
    : S_ISFIFO(st.st_mode) ? "a pipe"
    : S_ISSOCK(st.st_mode) ? "a socket"
                            : "not a regular file";
}

/**
 * Whether a writer may create or replace `path`: nothing is there, or a regular file (through
 * symbolic links), or the system does not say (creating it then reports why). Otherwise
 * `what` names what is there (vtkApertureFileKind): a writer must neither replace it (the EXR
 * writer renames its file into place) nor remove it after a failure (writing a GeoTIFF to
 * /dev/null fails, and the removal, run as root, deleted /dev/null).
 */
inline bool vtkApertureOutputReplaceable(const std::string& path, std::string& what)
{
  struct stat st;
  if (stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode))
  {
    return true;
  }
  what = vtkApertureFileKind(st);
  return false;
}

/** Whether a reader must refuse a file of this `st`: a named pipe or a socket, which the
 *  libraries' opens (GDAL's, OpenEXR's) would wait on for a writer, for ever when none comes,
 *  and could not seek in. */
inline bool vtkApertureUnreadableStream(const struct stat& st)
{
  return S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode);
}

#endif
