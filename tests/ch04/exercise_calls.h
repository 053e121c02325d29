// Chapter 4's exercise calls (tests/calls/calls.h): the tests of ex-4.9,
// ex-4.10, ex-4.11 and ex-4.12 reach Sphere::Area(), Disk::Area(),
// Triangle::Area() and Paraboloid::Area() only through these. Each call
// takes the arguments of the shape's constructor as values and builds the
// shape itself (with the inverse of the given transformation as
// WorldToObject).

#ifndef LRT_TESTS_CH04_EXERCISE_CALLS_H
#define LRT_TESTS_CH04_EXERCISE_CALLS_H

#include "lrt/shapes/sphere.h"
#include "lrt/shapes/disk.h"
#include "lrt/shapes/triangle.h"
#include "lrt/shapes/paraboloid.h"
#include "calls/calls.h"

#include <memory>
#include <stdexcept>
#include <vector>

namespace lrt {
namespace direct {

// Area() of Sphere(&objectToWorld, &inverse, reverseOrientation, radius,
// zMin, zMax, phiMax), called through the Shape interface.
inline Float SphereArea(Transform objectToWorld, bool reverseOrientation,
                        Float radius, Float zMin, Float zMax, Float phiMax) {
    Transform worldToObject = Inverse(objectToWorld);
    Sphere sphere(&objectToWorld, &worldToObject, reverseOrientation, radius,
                  zMin, zMax, phiMax);
    const Shape &shape = sphere;
    return shape.Area();
}

// Area() of Disk(&objectToWorld, &inverse, reverseOrientation, height,
// radius, innerRadius, phiMax), called through the Shape interface.
inline Float DiskArea(Transform objectToWorld, bool reverseOrientation,
                      Float height, Float radius, Float innerRadius,
                      Float phiMax) {
    Transform worldToObject = Inverse(objectToWorld);
    Disk disk(&objectToWorld, &worldToObject, reverseOrientation, height,
              radius, innerRadius, phiMax);
    const Shape &shape = disk;
    return shape.Area();
}

// Area() of Paraboloid(&objectToWorld, &inverse, reverseOrientation,
// radius, z0, z1, phiMax), called through the Shape interface.
inline Float ParaboloidArea(Transform objectToWorld, bool reverseOrientation,
                            Float radius, Float z0, Float z1, Float phiMax) {
    Transform worldToObject = Inverse(objectToWorld);
    Paraboloid paraboloid(&objectToWorld, &worldToObject, reverseOrientation,
                          radius, z0, z1, phiMax);
    const Shape &shape = paraboloid;
    return shape.Area();
}

// Area() of each triangle of the mesh that CreateTriangleMesh() makes of
// the vertex indices (three per triangle) and positions, in order.
inline std::vector<Float> TriangleMeshAreas(Transform objectToWorld,
                                            bool reverseOrientation,
                                            std::vector<int> vertexIndices,
                                            std::vector<Point3f> P) {
    Transform worldToObject = Inverse(objectToWorld);
    std::vector<std::shared_ptr<Shape>> triangles = CreateTriangleMesh(
        &objectToWorld, &worldToObject, reverseOrientation,
        int(vertexIndices.size() / 3), vertexIndices.data(), int(P.size()),
        P.data(), nullptr, nullptr, nullptr);
    std::vector<Float> areas;
    for (const std::shared_ptr<Shape> &t : triangles)
        areas.push_back(t->Area());
    return areas;
}

}  // namespace direct
}  // namespace lrt

LRT_EXERCISE_CALL(SphereArea)
LRT_EXERCISE_CALL(DiskArea)
LRT_EXERCISE_CALL(TriangleMeshAreas)
LRT_EXERCISE_CALL(ParaboloidArea)

namespace lrt {
namespace ex {

// The areas of a mesh's triangles, one per triangle (an answer of another
// length is an error, not a shorter list).
inline std::vector<Float> TriangleAreas(const Transform &objectToWorld,
                                        const std::vector<int> &vertexIndices,
                                        const std::vector<Point3f> &P) {
    std::vector<Float> areas =
        TriangleMeshAreas(objectToWorld, false, vertexIndices, P);
    if (areas.size() != vertexIndices.size() / 3)
        throw std::runtime_error("TriangleMeshAreas answered " +
                                 std::to_string(areas.size()) +
                                 " areas for " +
                                 std::to_string(vertexIndices.size() / 3) +
                                 " triangles");
    return areas;
}

// The area of the single triangle p0 p1 p2 of a mesh.
inline Float TriangleArea(const Transform &objectToWorld, const Point3f &p0,
                          const Point3f &p1, const Point3f &p2) {
    return TriangleAreas(objectToWorld, {0, 1, 2}, {p0, p1, p2})[0];
}

}  // namespace ex
}  // namespace lrt

#endif  // LRT_TESTS_CH04_EXERCISE_CALLS_H
