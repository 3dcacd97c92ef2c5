// SPDX-License-Identifier: BSD-3-Clause
// Private to Aperture::IO (not installed, not wrapped): OpenEXR's error messages for
// vtkApertureEXRReader and vtkApertureEXRWriter.
//
// OpenEXR reports errors through a callback given when a context is created, on the thread
// that made the failing call; its default callback prints to stderr. The callback cannot reach
// the reader or writer through exr_get_user_data(): for write contexts that call takes the
// context lock the failing call already holds, and deadlocks. So the calls run under a trap that
// registers itself for the current thread (innermost first) and keeps the last message.
#ifndef vtkApertureEXRErrorTrap_h
#define vtkApertureEXRErrorTrap_h

#include <openexr.h>

#include <string>

class vtkApertureEXRErrorTrap
{
public:
  vtkApertureEXRErrorTrap()
    : Previous(Current)
  {
    Current = this;
  }
  ~vtkApertureEXRErrorTrap() { Current = this->Previous; }
  vtkApertureEXRErrorTrap(const vtkApertureEXRErrorTrap&) = delete;
  vtkApertureEXRErrorTrap& operator=(const vtkApertureEXRErrorTrap&) = delete;

  /** The error callback: keeps the message in this thread's innermost trap (none: dropped). */
  static void Handler(exr_const_context_t, exr_result_t code, const char* message)
  {
    if (Current)
    {
      Current->Last = (message && *message) ? message : exr_get_default_error_message(code);
    }
  }

  /** Initializer for every context: this handler instead of the printing default. */
  static exr_context_initializer_t Initializer()
  {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = &vtkApertureEXRErrorTrap::Handler;
    return init;
  }

  /** Text for a failed call: the handler's message, else OpenEXR's text for the code. */
  std::string Message(exr_result_t code) const
  {
    return this->Last.empty() ? std::string(exr_get_default_error_message(code)) : this->Last;
  }

private:
  static inline thread_local vtkApertureEXRErrorTrap* Current = nullptr;
  vtkApertureEXRErrorTrap* Previous;
  std::string Last;
};

#endif
