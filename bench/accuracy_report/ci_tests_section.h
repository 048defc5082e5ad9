// ci_tests_section.h - the part of docs/ACCURACY.md that describes the CI tests of the accuracy suite which this
// report does not re-measure (hostile and oversized input, self-intersection, offset_ray GLSL parity, fuzzing).
#pragma once
#include <string>

namespace ht::accuracy::report {

// Markdown, starting with a "## " heading; figures are those of the CI tests as last measured (stated inline).
std::string ciTestsSection();

}  // namespace ht::accuracy::report
