// lrt/core/shape.cpp: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#include "lrt/core/shape.h"

#include <stdexcept>

namespace lrt {

// Shape Method Definitions
static const Transform *NonNullTransform(const Transform *t) {
    if (!t) throw std::invalid_argument("Shape: null transformation pointer");
    return t;
}

Shape::Shape(const Transform *ObjectToWorld, const Transform *WorldToObject,
             bool reverseOrientation)
    : ObjectToWorld(NonNullTransform(ObjectToWorld)),
      WorldToObject(NonNullTransform(WorldToObject)),
      reverseOrientation(reverseOrientation),
      transformSwapsHandedness(ObjectToWorld->SwapsHandedness()) {}

Shape::~Shape() {}
Bounds3f Shape::WorldBound() const { return (*ObjectToWorld)(ObjectBound()); }

}  // namespace lrt
