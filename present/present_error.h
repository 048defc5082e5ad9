// present_error.h - the error type of the display sink: no panel found, an ambiguous or unusable monitor, an X server
// or swapchain that cannot be used. The message names what was found and how to fix it (docs/DISPLAY.md).
#pragma once
#include "common/error.h"

namespace ht::present {

class PresentError : public Error {
 public:
  using Error::Error;
};

}  // namespace ht::present
