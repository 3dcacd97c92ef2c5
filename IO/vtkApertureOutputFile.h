// SPDX-License-Identifier: BSD-3-Clause
// Private to Aperture::IO: what the writers (vtkApertureDEMWriter, vtkApertureEXRWriter) may
// create or replace at their FileName.
#ifndef vtkApertureOutputFile_h
#define vtkApertureOutputFile_h

#include <sys/stat.h>

#include <string>

/**
 * Whether a writer may create or replace `path`: nothing is there, or a regular file (through
 * symbolic links), or the system does not say (creating it then reports why). Otherwise
 * `what` names what is there ("a folder", "a device", "a pipe", "a socket"): a writer must
 * neither replace it (the EXR writer renames its file into place) nor remove it after a
 * failure (writing a GeoTIFF to /dev/null fails, and the removal, run as root, deleted
 * /dev/null).
 */
inline bool vtkApertureOutputReplaceable(const std::string& path, std::string& what)
{
  struct stat st;
  if (stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode))
  {
    return true;
  }
  what = S_ISDIR(st.st_mode) ? "a folder"
    : (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) ? "a device"
    : S_ISFIFO(st.st_mode) ? "a pipe"
    : S_ISSOCK(st.st_mode) ? "a socket"
                            : "not a regular file";
  return false;
}

#endif
