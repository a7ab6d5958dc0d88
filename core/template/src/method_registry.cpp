// SPDX-License-Identifier: LGPL-2.1-or-later
// The registry of detection methods: adding a method is its file (with its factory) and a row below (the
// factory's declaration and the descriptor).
#include <stdexcept>
#include <string>

#include "colortrack/detection_method.hpp"

namespace colortrack {

std::unique_ptr<DetectionMethod> makeIndexingMethod(const MethodContext &context);  // method_indexing.cpp
std::unique_ptr<DetectionMethod> makeDiscriminativeMethod(
    const MethodContext &context);                                               // method_discriminative.cpp
std::unique_ptr<DetectionMethod> makeFusedMethod(const MethodContext &context);  // method_fused.cpp

const std::vector<MethodDescriptor> &methodDescriptors() {
  static const std::vector<MethodDescriptor> methods = {
      {Method::Indexing, "indexing", "Modified colour indexing: template histograms by intersection",
       makeIndexingMethod},
      {Method::Discriminative, "discriminative",
       "Colour only: object-versus-surroundings colour likelihood with a motion prior (fastest)",
       makeDiscriminativeMethod},
      {Method::Fused, "fused",
       "Shape (correlation filter) and colour fused, with confidence and re-detection (most accurate)",
       makeFusedMethod},
  };
  return methods;
}

std::unique_ptr<DetectionMethod> createDetectionMethod(Method method, const MethodContext &context) {
  for (const MethodDescriptor &d : methodDescriptors())
    if (d.value == method) return d.make(context);
  throw std::logic_error("no detection method registered for Method value " +
                         std::to_string(static_cast<int>(method)));
}

}  // namespace colortrack
