// SPDX-License-Identifier: BSD-3-Clause
// Private to Aperture::IO: what the writers (vtkApertureDEMWriter, vtkApertureEXRWriter) may
// create or replace at their FileName, and what the readers may not open (a named pipe).
#ifndef vtkApertureOutputFile_h
#define vtkApertureOutputFile_h

#include "vtkErrorCode.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

/** The ErrorCode a writer's Write() leaves, as VTK's writers set one, after it returned `ok`
 *  with the code `current` set where a failure was met (CannotOpenFileError; Write() refuses
 *  a missing name with NoFileNameError before it writes): NoError after success, else
 *  `current`, else UnknownError. (The code stayed NoError until 2026-12-07.) */
inline unsigned long vtkApertureWriteErrorCode(int ok, unsigned long current)
{
  if (ok)
  {
    return vtkErrorCode::NoError;
  }
  return current != vtkErrorCode::NoError ? current
                                          : static_cast<unsigned long>(vtkErrorCode::UnknownError);
}

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

/** The file a writer writes for `path`: through symbolic links (a relative one from its own
 *  folder, at most 40 of them) to their target, which need not exist yet, so that a link
 *  (latest.exr -> frames/0042.exr) stays a link and its target is written; else `path`. */
inline std::string vtkApertureOutputTarget(const std::string& path)
{
  std::string p = path;
  for (int k = 0; k < 40; ++k)
  {
    struct stat st;
    if (lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode))
    {
      return p;
    }
    std::vector<char> buffer(4096);
    const ssize_t n = readlink(p.c_str(), buffer.data(), buffer.size());
    if (n <= 0 || static_cast<size_t>(n) >= buffer.size())
    {
      return path;
    }
    std::string target(buffer.data(), static_cast<size_t>(n));
    const size_t slash = p.rfind('/');
    p = target[0] == '/' || slash == std::string::npos ? target : p.substr(0, slash + 1) + target;
  }
  return path; // (a loop of links: the open says so)
}

/** Whether a regular file is at `path` (through symbolic links) that this process may not write
 *  (access(2): its mode and owner; root may, as it may open one for writing): the writers,
 *  which write aside and rename into place, replaced such a read-only file, which an open for
 *  writing refuses, until 2026-12-07. */
inline bool vtkApertureOutputReadOnly(const std::string& path)
{
  const std::string target = vtkApertureOutputTarget(path);
  struct stat st;
  return stat(target.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
    access(target.c_str(), W_OK) != 0 && errno == EACCES;
}

/** The permission bits of the regular file at `path`, which a writer replacing it keeps (a
 *  file kept private, 0600, stayed so), or -1 when there is none. */
inline int vtkApertureExistingMode(const std::string& path)
{
  struct stat st;
  return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) ? static_cast<int>(st.st_mode & 07777)
                                                             : -1;
}

/** The hidden temporary file a writer writes before renaming it to `target` (its output,
 *  vtkApertureOutputTarget): ".aperture-<pid>-<n>.tmp" in the target's folder, a short name
 *  whatever the target's length, unique in the process (n counts). A failed write removes it
 *  and leaves an earlier file at the target as it was. */
inline std::string vtkApertureTemporaryName(const std::string& target)
{
  static std::atomic<unsigned long> count(0);
  const size_t slash = target.rfind('/');
  const size_t base = slash == std::string::npos ? 0 : slash + 1;
  return target.substr(0, base) + ".aperture-" + std::to_string(static_cast<long>(getpid())) +
    "-" + std::to_string(count++) + ".tmp";
}

/** Put a writer's complete `temporary` file in place of `target` (vtkApertureOutputTarget):
 *  with the permissions `mode` of the file it replaces (vtkApertureExistingMode; -1: the new
 *  file's own), then renamed over it. False, with errno saying why, when either fails; the
 *  temporary file is then the caller's to remove. */
inline bool vtkAperturePutInPlace(const std::string& temporary, const std::string& target, int mode)
{
  return (mode < 0 || chmod(temporary.c_str(), static_cast<mode_t>(mode)) == 0) &&
    std::rename(temporary.c_str(), target.c_str()) == 0;
}

/** After a writer put its new file at `target` (vtkApertureOutputTarget of `path`, the name
 *  it was given): removes the previous file's GDAL sidecars beside either, + ".aux.xml"
 *  (statistics, and a georeference GDAL takes before the file's own), ".ovr" (overviews of the
 *  old values, shown when zoomed out) and ".msk" (a mask), which GDAL would otherwise read
 *  with the new file; GDAL's own Create removes them too. "" when none is left, else a
 *  sentence for a warning naming the first one that could not be removed. */
inline std::string vtkApertureRemoveStaleSidecars(
  const std::string& path, const std::string& target)
{
  for (const std::string& name : { path, target })
  {
    for (const char* suffix : { ".aux.xml", ".ovr", ".msk" })
    {
      const std::string sidecar = name + suffix;
      struct stat st;
      if (lstat(sidecar.c_str(), &st) == 0 && unlink(sidecar.c_str()) != 0)
      {
        return "the previous file's sidecar '" + sidecar + "' stays beside the new one (" +
          std::strerror(errno) + "), and GDAL reads it with it: remove it";
      }
    }
  }
  return std::string();
}

/** Whether a reader must refuse a file of this `st`: a named pipe or a socket, which the
 *  libraries' opens (GDAL's, OpenEXR's) would wait on for a writer, for ever when none comes,
 *  and could not seek in. */
inline bool vtkApertureUnreadableStream(const struct stat& st)
{
  return S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode);
}

/** Why a reader cannot read `path`: "" when it can be opened for reading, else the system's
 *  reason ("Permission denied"; "No such file or directory" after stat failed). A library
 *  that cannot open it says it is not of its format (GDAL: "not a raster format GDAL
 *  recognises" for a file without read permission). */
inline std::string vtkApertureUnreadableReason(const char* path)
{
  const int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd >= 0)
  {
    close(fd);
    return std::string();
  }
  return std::strerror(errno);
}

/** The reader's message for `path` that stat(2) did not find (errno as it left it): that it
 *  does not exist, or why it cannot be reached (a folder on its way without permission). */
inline std::string vtkApertureMissingFileMessage(const std::string& path)
{
  return (errno == ENOENT || errno == ENOTDIR)
    ? "file '" + path + "' does not exist"
    : "cannot read '" + path + "': " + std::strerror(errno);
}

/** Why a writer cannot record the geotransform `gt` of an `nx` x `ny` grid of the image of
 *  `origin` and `spacing` in `path`: its edges are not finite numbers (a spacing of 1e308
 *  wrote a geotransform of inf, which no reader takes, until 2026-12-06); "" when it can. */
inline std::string vtkApertureGeoTransformProblem(const std::string& path, const double gt[6],
  int nx, int ny, const double origin[3], const double spacing[3])
{
  if (std::isfinite(gt[0]) && std::isfinite(gt[3]) && std::isfinite(gt[0] + nx * gt[1]) &&
    std::isfinite(gt[3] + ny * gt[5]))
  {
    return std::string();
  }
  std::ostringstream msg;
  msg << "cannot write '" << path << "': the grid's edges are not finite numbers (origin "
      << origin[0] << ", " << origin[1] << ", spacing " << spacing[0] << ", " << spacing[1]
      << ", " << nx << " x " << ny << " cells)";
  return msg.str();
}

/** Metadata a writer keeps for its file: `item` in place of the one `same` finds in `items`,
 *  else appended. A key added again replaces its value: a loop of writes adding one per frame
 *  grew the lists, and every write's time, without end (until 2026-12-07). */
template <typename T, typename Same>
void vtkApertureReplaceOrAppend(std::vector<T>& items, T item, Same same)
{
  const auto found = std::find_if(items.begin(), items.end(), same);
  if (found == items.end())
  {
    items.push_back(std::move(item));
  }
  else
  {
    *found = std::move(item);
  }
}

#endif
