// frame_images.cpp - see frame_images.h.
#include "frame_io/frame_images.h"

#include <string>

#include "common/error.h"

namespace ht::frame_io {

void checkImage(const RgbaImageView& image, const char* what) {
  checkFrame({image.width, image.height, 1, image.rgba}, what);
}

void checkFrame(const FrameImages& frame, const char* what) {
  if (frame.width == 0 || frame.height == 0 || frame.views == 0 ||
      frame.rgba.size() != frame.viewFloats() * frame.views) {
    throw IoError(std::string(what) + ": " + std::to_string(frame.views) + " views of " + std::to_string(frame.width) +
                  "x" + std::to_string(frame.height) + " with " + std::to_string(frame.rgba.size()) +
                  " floats, expected a non-empty frame of views*width*height*4 floats (a renderer bug)");
  }
}

}  // namespace ht::frame_io
