// lens_distortion_params.h - the GPU LensDistortion block of a configured lens, checked to be invertible.
#pragma once
#include <string>

#include <glm/glm.hpp>

#include "camera_models/camera_params.h"
#include "camera_models/lens_settings.h"

namespace ht {

// The block for `lens` (all zero: no distortion, radial.w = 0). `halfExtent` is the image's half width and height in
// distorted normalized coordinates (a pinhole: aspect tan(fovy/2), tan(fovy/2)); its corner is the largest radius
// the camera uses. Throws ConfigError(file, field, ...) when the lens folds before that
// radius (the radial profile r(1 + k1 r^2 + k2 r^4 + k3 r^6) stops increasing, so two directions would share a
// pixel and the inverse is ambiguous) or when the kernel's Newton inverse does not converge at the corners.
// The undistorted normalized point u with distort(u) = xd, in double (the references of the pinhole and projector
// models; the kernels use the float brown_conrady_undistort).
glm::dvec2 undistortReference(const LensDistortionSettings& lens, glm::dvec2 xd);

gpu_shared::LensDistortion makeLensDistortion(const LensDistortionSettings& lens, glm::dvec2 halfExtent,
                                              const std::string& file, const std::string& field);

}  // namespace ht
