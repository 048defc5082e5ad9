// request_checks.h - RenderRequest validation, before anything is queued or allocated: unknown ids -> NOT_FOUND,
// bad fields -> INVALID_ARGUMENT naming the field, limits -> RESOURCE_EXHAUSTED.
#pragma once
#include "holotrace/v1/holotrace.pb.h"
#include "server/frame_encoding.h"
#include "server/frame_job.h"
#include "server/service_state.h"

namespace ht::server {

FrameJob checkRenderRequest(ServiceState& state, const holotrace::v1::RenderRequest& request);
FrameEncoding checkPixelFormat(holotrace::v1::PixelFormat format);

}  // namespace ht::server
