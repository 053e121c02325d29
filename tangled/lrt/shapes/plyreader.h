// lrt/shapes/plyreader.h: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#pragma once

#include "lrt/core/geometry.h"
#include "lrt/core/shape.h"
#include "lrt/core/transform.h"

#include <memory>
#include <string>
#include <vector>

namespace lrt {

// PlyMesh Declarations
struct PlyMesh {
    std::vector<Point3f> p;
    std::vector<Normal3f> n;
    std::vector<Point2f> uv;
    std::vector<int> vertexIndices;
    int nVertices() const { return int(p.size()); }
    int nTriangles() const { return int(vertexIndices.size() / 3); }
};

// PLY Function Declarations
PlyMesh ReadPly(const std::string &filename);
std::vector<std::shared_ptr<Shape>> CreatePLYMesh(
    const Transform *ObjectToWorld, const Transform *WorldToObject,
    bool reverseOrientation, const std::string &filename);

}  // namespace lrt
