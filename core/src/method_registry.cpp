// The registry of detection methods: which factory makes the method for each `Method` value. Adding a method
// is a line in each of the two lists below (its factory, defined in its own file, and its case).
#include <stdexcept>
#include <string>

#include "colortrack/detection_method.hpp"

namespace colortrack {

std::unique_ptr<DetectionMethod> makeIndexingMethod(const MethodContext &context);  // method_indexing.cpp
std::unique_ptr<DetectionMethod> makeDiscriminativeMethod(
    const MethodContext &context);                                               // method_discriminative.cpp
std::unique_ptr<DetectionMethod> makeFusedMethod(const MethodContext &context);  // method_fused.cpp

std::unique_ptr<DetectionMethod> createDetectionMethod(Method method, const MethodContext &context) {
  // A switch without default: -Wswitch names a Method value added without its registration.
  switch (method) {
    case Method::Indexing:
      return makeIndexingMethod(context);
    case Method::Discriminative:
      return makeDiscriminativeMethod(context);
    case Method::Fused:
      return makeFusedMethod(context);
  }
  throw std::logic_error("no detection method registered for Method value " +
                         std::to_string(static_cast<int>(method)));
}

}  // namespace colortrack
